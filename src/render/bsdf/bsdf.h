// The BSDFs of spec §5 and §11 as the path tracer sees them: evaluate
// f(ωo, ωi), its sampling density, and draw ωi (spec §10–§11).
//
// Conventions. All directions are unit vectors in world space pointing away
// from the surface: wo towards the viewer (the camera path), wi towards the
// light. Lobes are computed in the local shading frame p.frame, where n_s is
// +z (cos θ = local z). The geometric normal decides which side a direction is
// on (spec §10 "No light leaks"): reflection needs wi on wo's side of n_g
// (n_g·wi > 0, n_g being on wo's side), transmission the other side
// (n_g·wi < 0); anything else has f = 0 and pdf = 0, and sample_bsdf returns
// false rather than produce it.
//
// The materials:
//  - Diffuse: f = kd/π. Sampled cosine-weighted around n_s: pdf = max(0, cos θ_i)/π.
//  - Phong (§5): f = kd/π + ks·(n+2)/(2π)·max(0, r·ωo)^n, r = ωi mirrored about n_s;
//    eval_bsdf returns exactly eval_brdf (render/bsdf/brdf.h) where wi is on wo's side.
//    Sampled by a mixture: the cosine lobe with probability P_d = mean(kd)/(mean(kd)+mean(ks)),
//    else ωi around r_o = ωo mirrored about n_s with density (n+1)/(2π)·max(0, ωi·r_o)^n
//    (ωi·r_o = r·ωo); pdf = P_d·cos⁺θ_i/π + (1 − P_d)·(n+1)/(2π)·max(0, ωi·r_o)^n.
//  - Mirror: delta; ωi = ωo mirrored about n_s, weight kr.
//  - Dielectric (§11): delta; exact unpolarised Fresnel F (1 under total internal
//    reflection) between η_i (wo's side: 1 if p.outside, else ior) and η_t (the other).
//    Reflection with probability F (weight 1), refraction by Snell's law with
//    probability 1 − F (weight kt·(η_i/η_t)², radiance transport).
//  - Conductor (§11): GGX with α = roughness², f = D(h)·G1(ωi)·G1(ωo)·F(ωo·h) / (4 cos θ_i cos θ_o),
//    h = normalize(ωi + ωo), Schlick F = ks + (1 − ks)(1 − ωo·h)⁵ (render/bsdf/microfacet.h).
//    Sampled by visible normals (Heitz 2018): pdf = D(h)·G1(ωo) / (4 cos θ_o), weight
//    F·G1(ωi). Directions drawn below n_s are failures, so the pdf integrates to ≤ 1.
//    α < 1e-3 is a delta mirror with weight F(cos θ_o) (as pbrt-v4).
//  - Pbr (§11, glTF 2.0 Appendix B; render/bsdf/bsdf_pbr.cpp): f = (1 − m)(1 − F_d)·c/π + ((1 − m)F_d + m·F_c)·V·D,
//    c = base_color, m = metallic, α = roughness², F_d Schlick from f0 = ((1 − ior)/(1 + ior))²,
//    F_c Schlick from f0 = c, both at ωo·h; V the height-correlated Smith visibility
//    G2/(4 cos θ_i cos θ_o) (microfacet.h). Sampled by a mixture: GGX visible normals with
//    probability P_s(cos θ_o) (Fresnel-weighted specular against diffuse albedo, in [0.25, 0.9],
//    1 for a black diffuse part), else cosine-weighted; pdf = P_s·D(h)G1(ωo)/(4 cos θ_o) +
//    (1 − P_s)·cos θ_i/π, weight f·cos θ_i/pdf. α < 1e-3: the specular part is a delta mirror
//    of weight ((1 − m)F_d + m·F_c)(cos θ_o)/P_s, chosen with probability P_s (BsdfSample::pdf);
//    eval and pdf hold the diffuse part only, and the material is delta only when m = 1.
// Non-delta lobes need cos θ_o > 0 and cos θ_i > 0 in the shading frame,
// except Diffuse and Phong, whose f is eval_brdf's wherever wi is on wo's side of n_g.
// Delta lobes need cos θ_o > 0 (a bumpy n_s facing away from wo gives false).
#pragma once

#include "core/frame.h"
#include "core/vec3.h"
#include "render/bsdf/brdf.h"
#include "scene/material.h"

namespace sombra {

// The surface as a BSDF sees it at a hit.
struct BsdfPoint {
    Vec3 n_g;     // unit geometric normal, on the side of wo (surfaces are two-sided)
    Vec3 n_s;     // unit shading normal, in n_g's hemisphere
    Frame frame;  // Frame::from_normal(n_s)
    bool
        outside;  // wo is on the side of the triangle's winding normal n_w (a dielectric ray from outside enters the medium)
    // The unit shading normal of a pbr material's KHR_materials_clearcoat
    // coat where it has its own (SurfaceInteraction::n_c), in n_g's
    // hemisphere; zero: the coat shares n_s and p.frame. Only the coat reads it.
    Vec3 n_c{};
};

// A BsdfPoint with its frame built around n_s. n_g, n_s unit, n_g·n_s ≥ 0;
// n_c zero or as BsdfPoint::n_c.
BsdfPoint make_bsdf_point(Vec3 n_g, Vec3 n_s, bool outside, Vec3 n_c = Vec3{});

// True when eval_bsdf, eval_bsdf_terms or pdf_bsdf of m read the shading
// frame (Conductor, Pbr). Diffuse and Phong work with n_s alone, and the
// delta materials evaluate to 0; sample_bsdf reads the frame for every
// material but those.
inline bool eval_reads_frame(const Material& m) {
    return m.type == MaterialType::Conductor || m.type == MaterialType::Pbr;
}

// A BsdfPoint for evaluating m only (eval_bsdf, eval_bsdf_terms, pdf_bsdf;
// never sample_bsdf): make_bsdf_point's where eval_reads_frame(m), else
// with the frame left zero, so that a diffuse or Phong hit of the direct
// integrator, which only evaluates, builds no frame it would not read.
inline BsdfPoint make_eval_bsdf_point(const Material& m, Vec3 n_g, Vec3 n_s, bool outside, Vec3 n_c = Vec3{}) {
    if (eval_reads_frame(m)) return make_bsdf_point(n_g, n_s, outside, n_c);
    return BsdfPoint{n_g, n_s, Frame{}, outside};
}

struct BsdfSample {
    Vec3 wi;        // sampled unit direction, world space, pointing away from the surface
    Vec3 weight;    // f(wo, wi)·|n_s·wi| / pdf; for a delta lobe the lobe's factor / its selection probability
    float pdf = 0;  // solid-angle density of wi (for MIS); for a delta lobe: the probability of having chosen that lobe
    bool delta = false;  // wi came from a delta (specular) lobe: eval/pdf of it are 0, no MIS against lights
    bool transmission = false;
};

// The roughness α below which a Conductor, or a Pbr's specular part, is a delta mirror.
inline constexpr float kDeltaAlpha = 1e-3f;

// True when m has a non-delta transmission lobe, so that eval_bsdf and
// pdf_bsdf may be > 0 for wi on the other side of n_g: a rough pbr with
// KHR_materials_transmission, on a thin wall (thickness 0) or bounding a
// volume that refracts (thickness > 0, ior > 1: Walter et al.'s rough
// refraction). Every other transmission (Dielectric, a smooth pbr's, a
// volume's of ior ≤ 1, which does not bend the ray) is a delta.
inline bool transmits_diffusely(const Material& m) {
    return m.type == MaterialType::Pbr && m.transmission > 0.0f && m.metallic < 1.0f &&
           (!(m.thickness > 0.0f) || m.ior > 1.0f) && m.roughness * m.roughness >= kDeltaAlpha;
}

// False when sample_bsdf's result does not depend on u_lobe for m (one
// lobe, or a choice it makes by other means), so that a caller may leave
// that random number uncomputed.
inline bool uses_lobe_choice(const Material& m) {
    return m.type == MaterialType::Phong || m.type == MaterialType::Dielectric || m.type == MaterialType::Pbr;
}

// The factor by which a transmission sampled by sample_bsdf at a point
// whose wo is `outside` (BsdfPoint::outside) scales (η_i/η_t)²: what undoes
// refraction's radiance scaling for Russian roulette. Dielectric and a
// pbr bounding a volume of ior > 1 (KHR_materials_volume) refract: ior² from
// outside, 1/ior² from inside; 1 for the thin walls, which do not.
float transmission_eta_scale(const Material& m, bool outside);

// eval_bsdf of the materials other than Diffuse and Phong, for wi on wo's
// side of n_g (eval_bsdf has checked it), or on the other side when
// transmits_diffusely(m).
Vec3 eval_bsdf_other(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);

// f(wo, wi) in 1/sr of the non-delta lobes (0 for Mirror, Dielectric and
// smooth Conductor; a smooth Pbr's diffuse part); 0 where the no-light-leak rule says so.
// Diffuse and Phong, whose f is eval_brdf's, are evaluated inline: the light
// loops call this once per light, and an out-of-line call there costs as
// much as the Lambert term itself (spills of the loop's registers around it).
inline Vec3 eval_bsdf(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    if (dot(p.n_g, wi) <= 0.0f) return transmits_diffusely(m) ? eval_bsdf_other(m, p, wo, wi) : Vec3{0.0f};
    if (m.type == MaterialType::Diffuse || m.type == MaterialType::Phong) return eval_brdf(m, p.n_s, wi, wo);
    return eval_bsdf_other(m, p, wo, wi);
}

// f(wo, wi) split as spec §4 and §14 name its parts, for `sombra explain`:
// the diffuse term (kd/π) and the lobe (Phong's specular lobe, or the
// microfacet lobe). Their sum is eval_bsdf's value up to float rounding;
// the integrators use eval_bsdf's.
struct BsdfTerms {
    Vec3 diffuse, lobe;
    // pbr's KHR_materials_transmission lobe through a rough thin wall or a
    // rough volume's interface (wi on the other side of n_g),
    // KHR_materials_clearcoat's coat and
    // KHR_materials_sheen's sheen; 0 elsewhere. The sum of all five is
    // eval_bsdf's value up to float rounding.
    Vec3 transmission{0.0f}, coat{0.0f}, sheen{0.0f};
};
BsdfTerms eval_bsdf_terms(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);

// The lobes as explain lists them (spec §14), in its order: the name it
// prints, whether it is shown when 0, and the term of BsdfTerms. A new lobe
// is a term above and a row here; explain iterates the table.
struct LobeName {
    const char* name;
    bool always_shown;
    Vec3 BsdfTerms::*term;
};
inline constexpr LobeName kLobeNames[] = {{"diffuse", true, &BsdfTerms::diffuse},
                                          {"lobe", true, &BsdfTerms::lobe},
                                          {"transmission", false, &BsdfTerms::transmission},
                                          {"coat", false, &BsdfTerms::coat},
                                          {"sheen", false, &BsdfTerms::sheen}};

// Solid-angle density (1/sr) with which sample_bsdf draws wi: non-delta lobes
// only, 0 for a delta material and wherever sample_bsdf never succeeds.
float pdf_bsdf(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);

// Draws wi. u_lobe in [0,1) picks a lobe, (u1, u2) in [0,1)² place the
// direction. Returns false, leaving out unspecified, when no direction was
// produced (below the surface or on the wrong side of n_g, cos θ_o ≤ 0 for a
// lobe that needs it, zero weight).
bool sample_bsdf(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2, BsdfSample& out);

// True when every lobe of m is a delta (Mirror, Dielectric, Conductor with
// α = roughness² < 1e-3, Pbr with that α and metallic 1): lights cannot be sampled for it.
bool is_delta_bsdf(const Material& m);

// Exact unpolarised Fresnel reflectance of a smooth dielectric interface for
// light arriving at cos_i (> 0) in a medium of index eta_i onto one of index
// eta_t: (R_s + R_p)/2, 1 under total internal reflection.
float fresnel_dielectric(float cos_i, float eta_i, float eta_t);

}  // namespace sombra
