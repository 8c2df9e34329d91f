// Building blocks that the BSDFs of render/bsdf/bsdf.cpp and render/bsdf/bsdf_pbr.cpp
// share: mirror reflection, the cosine-weighted and uniform hemispheres and
// the delta mirror lobe. Internal to render/ (bsdf.h is the interface).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/vec3.h"
#include "render/bsdf/bsdf.h"

namespace sombra {

// 2(w·n)n − w: w mirrored about the unit normal n.
inline Vec3 reflect(Vec3 w, Vec3 n) { return 2.0f * dot(w, n) * n - w; }

// A cosine-weighted direction around +z (density cos θ/π): Malley's method,
// z = sqrt(1 − u1) > 0 for u1 in [0, 1).
inline Vec3 sample_cosine_hemisphere(float u1, float u2) {
    const float r = std::sqrt(u1);
    const float phi = 2.0f * std::numbers::pi_v<float> * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1))};
}

// A uniformly distributed direction around +z (density 1/(2π)), z = 1 − u1 > 0
// for u1 in [0, 1).
inline Vec3 sample_uniform_hemisphere(float u1, float u2) {
    const float z = 1.0f - u1;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * std::numbers::pi_v<float> * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// The delta lobe ωi = ωo mirrored about n_s with the given weight and pdf (a
// lobe's selection probability); false when ωi falls below n_g or the weight is 0.
inline bool sample_specular_reflection(const BsdfPoint& p, Vec3 wo, Vec3 weight, float pdf, BsdfSample& out) {
    const Vec3 wi = reflect(wo, p.n_s);
    if (dot(p.n_g, wi) <= 0.0f || !(max_component(weight) > 0.0f)) return false;
    out = BsdfSample{wi, weight, pdf, true, false};
    return true;
}

}  // namespace sombra
