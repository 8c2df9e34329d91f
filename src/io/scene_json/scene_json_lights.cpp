// The "lights" section of a scene file: point lights (spec §4), spot and
// directional lights (§16), and quad lights (§10, read in
// scene_json_quad_light.cpp), each validated as the spec asks.
#include <cmath>

#include "core/format.h"
#include "core/vec3d.h"
#include "io/scene_json/scene_json.h"

namespace sombra {
namespace {

// A direction that must not be zero (it is normalised when the light is made).
Vec3 read_direction(const SceneJson& s, const Json& light, std::string_view pointer) {
    const std::string p = json_child(pointer, "direction");
    const Vec3 d = read_vec3(s, require_member(s, light, pointer, "direction"), p);
    if (!(length(to_double(d)) > 0)) json_fail(s, p, "direction is zero");
    return d;
}

// An angle in degrees within [lo, hi].
float read_angle(const SceneJson& s, const Json& v, std::string_view pointer, float lo, float hi, const char* range) {
    const float degrees = read_float(s, v, pointer);
    if (!(degrees >= lo && degrees <= hi))
        // append, not operator+: GCC 12 warns falsely on a literal + std::string (-Wrestrict, bug 105329).
        json_fail(s, pointer,
                  std::string("angle ").append(format_number(degrees)).append(" is outside ").append(range));
    return degrees;
}

PunctualLight read_point_light(const SceneJson& s, const Json& light, std::string_view p) {
    expect_keys(s, light, p, {"type", "position", "intensity"});
    return make_point_light(read_vec3(s, require_member(s, light, p, "position"), json_child(p, "position")),
                            read_rgb(s, require_member(s, light, p, "intensity"), json_child(p, "intensity")));
}

// {"type": "spot", position, direction, intensity, outer_angle (45), inner_angle (0)}:
// 0 ≤ inner ≤ outer ≤ 90 and outer > 0, in degrees.
PunctualLight read_spot_light(const SceneJson& s, const Json& light, std::string_view p) {
    expect_keys(s, light, p, {"type", "position", "direction", "intensity", "outer_angle", "inner_angle"});
    const Vec3 position = read_vec3(s, require_member(s, light, p, "position"), json_child(p, "position"));
    const Vec3 direction = read_direction(s, light, p);
    const Vec3 intensity = read_rgb(s, require_member(s, light, p, "intensity"), json_child(p, "intensity"));
    float outer = 45, inner = 0;
    if (const Json* v = find_member(light, "outer_angle")) {
        const std::string q = json_child(p, "outer_angle");
        outer = read_angle(s, *v, q, 0, 90, "(0, 90] degrees");
        if (outer == 0) json_fail(s, q, "a spot light's outer_angle must be greater than 0 degrees");
    }
    if (const Json* v = find_member(light, "inner_angle"))
        inner = read_angle(s, *v, json_child(p, "inner_angle"), 0, 90, "[0, 90] degrees");
    if (inner > outer)
        json_fail(s, json_child(p, "inner_angle"),
                  "inner_angle " + format_number(inner) + " is larger than outer_angle " + format_number(outer));
    return make_spot_light(position, direction, intensity, outer, inner);
}

// {"type": "directional", direction, irradiance}.
PunctualLight read_directional_light(const SceneJson& s, const Json& light, std::string_view p) {
    expect_keys(s, light, p, {"type", "direction", "irradiance"});
    const Vec3 direction = read_direction(s, light, p);
    return make_directional_light(direction,
                                  read_rgb(s, require_member(s, light, p, "irradiance"), json_child(p, "irradiance")));
}

}  // namespace

SceneLights read_lights(const SceneJson& s, const Json& v, std::string_view pointer) {
    expect_array(s, v, pointer);
    SceneLights lights;
    for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string p = json_child(pointer, i);
        const Json& light = v[i];
        expect_object(s, light, p);
        std::string type = "point";
        if (const Json* t = find_member(light, "type")) type = read_string(s, *t, json_child(p, "type"));
        if (type == "point")
            lights.punctual.push_back(read_point_light(s, light, p));
        else if (type == "spot")
            lights.punctual.push_back(read_spot_light(s, light, p));
        else if (type == "directional")
            lights.punctual.push_back(read_directional_light(s, light, p));
        else if (type == "quad")
            lights.quads.push_back(read_quad_light(s, light, p));
        else
            json_fail(s, json_child(p, "type"),
                      "unknown light type '" + type + "' (expected 'point', 'spot', 'directional' or 'quad')");
    }
    return lights;
}

}  // namespace sombra
