// The BRDFs of spec §5: f_r(ω_i, ω_o), per RGB channel, in 1/sr.
#pragma once

#include <cmath>
#include <numbers>

#include "core/vec3.h"
#include "scene/material.h"

namespace sombra {

inline constexpr float kInvPi = std::numbers::inv_pi_v<float>;

// Lambert: kd / π, the same in every direction.
inline Vec3 eval_lambert(Vec3 kd) { return kd * kInvPi; }

// The specular lobe of the energy-normalised modified Phong BRDF:
// (n + 2) / (2π) · max(0, r·ω_o)^n with r = 2(n_s·ω_i)n_s − ω_i, the mirror
// direction of ω_i about the shading normal. 0⁰ = 1, so n = 0 is a constant lobe.
inline float eval_phong_lobe(Vec3 n_s, Vec3 wi, Vec3 wo, float shininess) {
    const Vec3 r = 2.0f * dot(n_s, wi) * n_s - wi;
    const float cos_alpha = std::max(0.0f, dot(r, wo));
    return (shininess + 2.0f) * (0.5f * kInvPi) * std::pow(cos_alpha, shininess);
}

// f_r for a material. n_s: unit shading normal; wi: unit direction towards
// the light; wo: unit direction towards the viewer (all world space).
inline Vec3 eval_brdf(const Material& material, Vec3 n_s, Vec3 wi, Vec3 wo) {
    Vec3 f = eval_lambert(material.kd);
    if (material.type == MaterialType::Phong) f += material.ks * eval_phong_lobe(n_s, wi, wo, material.shininess);
    return f;
}

}  // namespace sombra
