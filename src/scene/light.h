// Delta lights (spec §4, §16): lights whose light arrives at a point from a
// single direction, so that no ray can hit them and only next-event
// estimation finds them. What scene files list besides quad lights (which
// become emitting triangles), and what glTF's KHR_lights_punctual brings.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/vec3.h"
#include "core/vec3d.h"
#include "scene/transform.h"

namespace sombra {

enum class LightType : std::uint8_t {
    Point,        // from `position` equally in every direction
    Spot,         // from `position`, inside a cone about `direction`
    Directional,  // from infinitely far, travelling along `direction`
};

// What a type of light has, one row per type: what explain shows of it and
// what a transform moves (transform_light).
struct LightTypeTraits {
    const char* name;          // "point", "spot", "directional": the scene file's and explain's word
    bool positioned;           // it sits at `position`, at a finite distance
    bool directed;             // it has a `direction`: a spot's axis, the way a sun's light travels
    bool coned;                // a spot's cone (cos_outer, cos_inner) and falloff
    const char* power_key;     // what `intensity` holds: "intensity" (I, W/sr) or "irradiance" (E, W/m²)
    const char* power_symbol;  // "I" or "E"
};

constexpr LightTypeTraits light_type_traits(LightType type) {
    switch (type) {
        case LightType::Spot: return {"spot", true, true, true, "intensity", "I"};
        case LightType::Directional: return {"directional", false, true, false, "irradiance", "E"};
        case LightType::Point: break;
    }
    return {"point", true, false, false, "intensity", "I"};
}

// One record for the three kinds: what each needs fits in a few floats, and
// the integrators switch on `type` (no virtual call per shadow ray).
struct PunctualLight {
    LightType type = LightType::Point;
    Vec3 position;   // point, spot
    Vec3 direction;  // unit; spot: the cone's axis (away from the light); directional: the way the light travels
    // Point and spot: radiant intensity I (W/sr, RGB), on the axis for a spot.
    // Directional: irradiance E (W/m², RGB) on a surface facing the light.
    Vec3 intensity;
    // Spot: cosines of the outer and inner cone angles (cos_outer < cos_inner
    // unless the two angles are equal).
    float cos_outer = -1;
    float cos_inner = 1;
};

inline PunctualLight make_point_light(Vec3 position, Vec3 intensity) {
    PunctualLight light;
    light.position = position;
    light.intensity = intensity;
    return light;
}

// `v` scaled to unit length, in double so that vectors too short or too long
// to square in float still give their direction. v must be finite and non-zero.
inline Vec3 unit_direction(Vec3 v) {
    const Vec3d d = to_double(v);
    const double len = length(d);
    return to_float(Vec3d{d.x / len, d.y / len, d.z / len});
}

// Angles in degrees from the axis, 0 ≤ inner ≤ outer ≤ 90 and outer > 0
// (checked by the readers); `axis` need not be unit length.
inline PunctualLight make_spot_light(Vec3 position, Vec3 axis, Vec3 intensity, float outer_degrees,
                                     float inner_degrees) {
    constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;
    PunctualLight light;
    light.type = LightType::Spot;
    light.position = position;
    light.direction = unit_direction(axis);
    light.intensity = intensity;
    light.cos_outer = static_cast<float>(std::cos(outer_degrees * kRadiansPerDegree));
    light.cos_inner = static_cast<float>(std::cos(inner_degrees * kRadiansPerDegree));
    return light;
}

inline PunctualLight make_directional_light(Vec3 direction, Vec3 irradiance) {
    PunctualLight light;
    light.type = LightType::Directional;
    light.direction = unit_direction(direction);
    light.intensity = irradiance;
    return light;
}

// What placing a light by a transform can break.
enum class LightPlacement {
    Ok,
    NonFinitePosition,   // a point or spot light's position overflows
    NonFiniteDirection,  // a spot's or directional light's direction overflows or vanishes
};

// Carries `light` by `transform` (a glTF node's, a scene object's): the
// position of a point or spot light moves, the direction of a spot or
// directional light turns with the linear part and is renormalised. On a
// problem the light is left unusable and the caller reports it.
inline LightPlacement transform_light(PunctualLight& light, const Transform& transform) {
    const LightTypeTraits traits = light_type_traits(light.type);
    if (traits.positioned) {
        light.position = transform_point(transform, light.position);
        if (!is_finite(light.position)) return LightPlacement::NonFinitePosition;
    }
    if (traits.directed) {
        const Vec3 direction = transform_vector(transform, light.direction);
        if (!is_finite(direction) || !(length(to_double(direction)) > 0)) return LightPlacement::NonFiniteDirection;
        light.direction = unit_direction(direction);
    }
    return LightPlacement::Ok;
}

// A spot light's falloff at a direction `cos_axis` = cos θ from its axis,
// squared as spec §16 applies it: s² with s = clamp((cos θ − cos outer) /
// max(10⁻³, cos inner − cos outer), 0, 1) (KHR_lights_punctual's smooth
// falloff). 1 inside the inner cone, 0 outside the outer one.
inline float spot_falloff(const PunctualLight& light, float cos_axis) {
    const float s = (cos_axis - light.cos_outer) / std::fmax(1e-3f, light.cos_inner - light.cos_outer);
    const float clamped = std::fmin(std::fmax(s, 0.0f), 1.0f);
    return clamped * clamped;
}

}  // namespace sombra
