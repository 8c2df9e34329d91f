// Refraction through a rough interface between two dielectrics, GGX
// microfacets (render/bsdf/microfacet.h) as Walter, Marschner, Li and Torrance
// 2007 ("Microfacet Models for Refraction through Rough Surfaces", EGSR)
// write it: the generalized half vector of a pair of directions on opposite
// sides, the Jacobian from microfacet normals to refracted directions, and
// the refraction of ωo about one microfacet normal.
//
// Frame: unit vectors in the local shading frame, n_s = +z, ωo above the
// surface (z > 0) and a refracted ωi below. eta is η_o/η_t, the index of
// refraction on ωo's side over the one on the other side: spec §11's
// η_i/η_t (the side the camera path arrives from over the side it enters),
// 1/ior entering a volume, ior leaving it. eta ≠ 1: with equal indices the
// half vector is undefined (the surface does not bend the light at all).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/vec3.h"

namespace sombra {

// ωi = ωo refracted about the unit microfacet normal h by Snell's law,
// −eta·ωo + (eta·(ωo·h) − cos θ_t)·h; false under total internal reflection
// (sin²θ_t = eta²(1 − (ωo·h)²) ≥ 1), when no ray crosses that facet.
// ωo·h must be > 0.
inline bool refract_about(Vec3 wo, Vec3 h, float eta, Vec3& wi) {
    const float c = dot(wo, h);
    const float sin2_t = eta * eta * std::max(0.0f, 1.0f - c * c);
    if (sin2_t >= 1.0f) return false;
    const float cos_t = std::sqrt(1.0f - sin2_t);
    wi = normalize(-eta * wo + (eta * c - cos_t) * h);
    return true;
}

// The generalized half vector −(η_t ωi + η_o ωo), normalised and turned to
// the +z side (Walter et al. eq. 16, divided through by η_t): the only
// microfacet normal that refracts ωo into ωi. Not finite when eta·ωo + ωi
// is 0; the caller's facing tests (ωo·h > 0 > ωi·h) then fail, as they do
// for a pair that no facet refracts into each other.
inline Vec3 refraction_half_vector(Vec3 wo, Vec3 wi, float eta) {
    const Vec3 h = normalize(eta * wo + wi);
    return h.z < 0.0f ? -h : h;
}

// |∂ω_h/∂ω_i| = |ωi·h| / (ωi·h + eta·(ωo·h))² (Walter et al. eq. 17 with
// η_t² divided out, in 1/sr per 1/sr): the density of microfacet normals
// becomes one of refracted directions by this factor. 0 where the
// denominator vanishes (eta = 1).
inline float refraction_jacobian(Vec3 wo, Vec3 wi, Vec3 h, float eta) {
    const float cos_ih = dot(wi, h);
    const float d = cos_ih + eta * dot(wo, h);
    return d * d > 0.0f ? std::fabs(cos_ih) / (d * d) : 0.0f;
}

}  // namespace sombra
