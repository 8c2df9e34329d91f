// Radiance arriving from infinitely far away, by direction (spec §10). This
// first version holds a constant colour only (the scene's background under
// the path integrator); equirectangular maps come with the envmap work.
#pragma once

#include "core/vec3.h"

namespace sombra {

struct Environment {
    Vec3 constant{0.0f};
};

inline Environment make_constant_environment(Vec3 radiance) { return Environment{radiance}; }
inline bool is_black(const Environment& env) { return max_component(env.constant) <= 0.0f; }

// Radiance arriving from `direction` (unit, world space, pointing away from the scene).
inline Vec3 eval_environment(const Environment& env, Vec3 /*direction*/) { return env.constant; }

struct EnvironmentSample {
    Vec3 direction;
    Vec3 radiance;
    float pdf;  // with respect to solid angle
};
bool sample_environment(const Environment& env, float u1, float u2, EnvironmentSample& out);
float pdf_environment(const Environment& env, Vec3 direction);
// ∫ luminance(L(ω)) dω over the sphere: weighs the environment against area
// lights (times π R² of the scene's bounding sphere).
float environment_power_proxy(const Environment& env);

}  // namespace sombra
