// What arrives at a point from one delta light (spec §4, §16), said once for
// the integrators' next-event estimation (render/delta_lights.h) and for
// explain's recorder: each type of light gives, in a file of its own
// (point_light.h, spot_light.h, directional_light.h), where its light
// arrives from (the arrival) and its own factor in that direction (a spot's
// falloff), and delta_light_types.h chooses among them. The factor is asked
// for only once the light is known to face the point.
#pragma once

#include <cmath>

#include "core/ray.h"
#include "core/vec3.h"
#include "scene/light.h"

namespace sombra {

// Sixteen bytes, what the loop over lights needs, so that it stays in a register.
struct DeltaArrival {
    Vec3 wi{0.0f};  // unit direction from the point towards the light
    // |c − x|²: +∞ for a light at infinity, 0 for a light on the surface.
    float distance_squared = 0;
};

// The light sits exactly at the point: it lights nothing.
inline bool on_surface(const DeltaArrival& a) { return !(a.distance_squared > 0.0f); }

// The inverse-square law's divisor: |c − x|², 1 for a light at infinity (E has no falloff).
inline float inverse_square_divisor(const PunctualLight& light, const DeltaArrival& a) {
    return light_type_traits(light.type).positioned ? a.distance_squared : 1.0f;
}

// What leaves `light` towards the point: its I (or E) times its own factor
// in that direction (delta_light_types.h's delta_factor; x·1 is x: a point
// light's I exactly).
inline Vec3 emitted_towards(const PunctualLight& light, float factor) { return light.intensity * factor; }

// The shadow ray from `origin` (the offset hit point) towards the light. A
// light at infinity's has no end; a positioned light's reaches it at t = 1,
// and the bound just short of it keeps the light's own position (possibly
// on a surface) from counting as an occluder.
inline Ray delta_shadow_ray(const PunctualLight& light, const DeltaArrival& a, Vec3 origin) {
    return light_type_traits(light.type).positioned ? Ray{origin, light.position - origin, 1.0f - 1e-5f}
                                                    : Ray{origin, a.wi};
}

// What explain prints of an arrival: I/|c − x|² and the like, the factor the
// integrator multiplies f_r · |n_s·ω_i| by (E/1 is E exactly).
inline Vec3 incident_radiance_factor(const PunctualLight& light, const DeltaArrival& a, float factor) {
    return emitted_towards(light, factor) / inverse_square_divisor(light, a);
}

// The arrival from a light at `position`, before any factor of its own.
inline DeltaArrival arrival_from_position(Vec3 position, Vec3 x) {
    const Vec3 to_light = position - x;
    const float distance_squared = dot(to_light, to_light);
    if (!(distance_squared > 0.0f)) return {};  // on the surface: no direction
    return {to_light / std::sqrt(distance_squared), distance_squared};
}

}  // namespace sombra
