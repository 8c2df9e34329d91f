// The GGX (Trowbridge–Reitz) microfacet distribution of spec §11's conductor,
// isotropic, with roughness α (α = r² of the material's roughness r).
//
// Frame: every vector here is a unit vector in the local shading frame
// (render/bsdf/bsdf.h's BsdfPoint::frame), where the shading normal n_s is +z, so
// cos θ = w.z. Every function is finite for any unit input as long as α > 0
// (the BSDF treats α < 1e-3 as a delta mirror and never calls these with it).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/vec3.h"

namespace sombra {

// D(h), in 1/sr (of microfacet normals, per unit projected area):
// α² / (π (cos²θ_h (α² − 1) + 1)²), written as 1 / (π α² ((x² + y²)/α² + z²)²)
// so that it stays finite for small α. 0 for h.z ≤ 0.
inline float ggx_d(Vec3 h, float alpha) {
    if (h.z <= 0.0f) return 0.0f;
    const float a2 = alpha * alpha;
    const float e = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
    return 1.0f / (std::numbers::pi_v<float> * a2 * e * e);
}

// Smith's masking G1(w) divided by |cos θ_w|: 2 / (|z| + sqrt(z² + α²(x² + y²))),
// i.e. G1 = 1 / (1 + Λ) with Λ = (−1 + sqrt(1 + α² tan²θ)) / 2, over |cos θ|.
// Never divides by 0 for α > 0, which is why the BSDF uses it instead of G1 / cos.
inline float ggx_g1_over_cos(Vec3 w, float alpha) {
    const float z = std::fabs(w.z);
    const float s2 = std::max(0.0f, w.x * w.x + w.y * w.y);
    return 2.0f / (z + std::sqrt(z * z + alpha * alpha * s2));
}

// Smith's masking G1(w) in [0, 1]: 1 at normal incidence, 0 at grazing.
inline float ggx_g1(Vec3 w, float alpha) { return std::fabs(w.z) * ggx_g1_over_cos(w, alpha); }

// A microfacet normal h drawn from the distribution of normals visible from
// wo, D_wo(h) = G1(wo) · max(0, wo·h) · D(h) / cos θ_o (Heitz 2018, "Sampling
// the GGX Distribution of Visible Normals", JCGT 7(4)). wo.z must be > 0;
// (u1, u2) in [0, 1)². The result has h.z ≥ 0 and wo·h ≥ 0.
inline Vec3 sample_ggx_vndf(Vec3 wo, float alpha, float u1, float u2) {
    // Stretch wo to the configuration where the microsurface is a hemisphere.
    const Vec3 vh = normalize(Vec3{alpha * wo.x, alpha * wo.y, wo.z});
    // An orthonormal basis (t1, t2, vh), t1 horizontal; any t1 when vh is the pole.
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = len2 > 0.0f ? Vec3{-vh.y, vh.x, 0.0f} / std::sqrt(len2) : Vec3{1.0f, 0.0f, 0.0f};
    const Vec3 t2 = cross(vh, t1);
    // A point on the unit disk, warped towards the part of the projected
    // hemisphere that vh sees.
    const float r = std::sqrt(u1);
    const float phi = 2.0f * std::numbers::pi_v<float> * u2;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * (r * std::sin(phi));
    // Project onto the hemisphere and unstretch.
    const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return normalize(Vec3{alpha * nh.x, alpha * nh.y, std::max(1e-9f, nh.z)});
}

// The solid-angle density of ωi = ωo mirrored about an h drawn by
// sample_ggx_vndf: D_wo(h) / (4 ωo·h) = D(h)·G1(ωo) / (4 cos θ_o). 0 unless
// both directions are above the shading plane.
inline float ggx_reflection_pdf(Vec3 wo, Vec3 wi, float alpha) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    const Vec3 h = normalize(wi + wo);
    return 0.25f * ggx_d(h, alpha) * ggx_g1_over_cos(wo, alpha);
}

// The height-correlated Smith visibility term of spec §11's pbr (the glTF 2.0
// specification's Appendix B, "Specular BRDF"): V = G2 / (4 cos θ_i cos θ_o)
// with G2 = 1 / (1 + Λ(ωi) + Λ(ωo)) (Heitz 2014), which simplifies to
// 1 / (2 (cos θ_o sqrt(α² + (1 − α²) cos²θ_i) + cos θ_i sqrt(α² + (1 − α²) cos²θ_o))).
// α² + (1 − α²) z² is written z² + α² (x² + y²), as in ggx_g1_over_cos. Both
// directions must be above the shading plane (z > 0); the result is finite there for α > 0.
inline float ggx_v_height_correlated(Vec3 wo, Vec3 wi, float alpha) {
    const float a2 = alpha * alpha;
    const float root_i = std::sqrt(wi.z * wi.z + a2 * std::max(0.0f, wi.x * wi.x + wi.y * wi.y));
    const float root_o = std::sqrt(wo.z * wo.z + a2 * std::max(0.0f, wo.x * wo.x + wo.y * wo.y));
    return 0.5f / (wo.z * root_i + wi.z * root_o);
}

// Schlick's Fresnel of spec §11: F = f0 + (1 − f0)(1 − cos)⁵, cos clamped to [0, 1].
inline Vec3 fresnel_schlick(Vec3 f0, float cos_theta) {
    const float c = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
    const float c2 = c * c;
    return f0 + (Vec3{1.0f} - f0) * (c2 * c2 * c);
}

}  // namespace sombra
