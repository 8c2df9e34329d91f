// Spec §11's `pbr`: the glTF 2.0 metallic–roughness BRDF of the glTF
// specification's Appendix B, in its mix form,
//
//   f = (1 − m)·fresnel_mix(ior, diffuse_brdf(c), specular_brdf(α)) + m·conductor_fresnel(c, specular_brdf(α))
//     = (1 − m)(1 − max(F_d))·c/π  +  ((1 − m)·F_d + m·F_c)·V·D     ("diffuse" + "specular" below)
//
// with c = base_color, m = metallic, α = roughness², D the GGX distribution
// (render/microfacet.h), F_d = Schlick with f0 = ((1 − ior)/(1 + ior))² and
// F_c = Schlick with f0 = c, both at ωo·h, h = normalize(ωi + ωo). glTF's
// KHR_materials_specular makes F_d coloured and weighted (dielectric_fresnel
// below; max(F_d) is its max_value); without it F_d is grey and max(F_d) = F_d.
//
// V is the height-correlated Smith visibility G2/(4 cos θ_i cos θ_o),
// G2 = 1/(1 + Λ(ωi) + Λ(ωo)), because Appendix B ("Specular BRDF") defines
// specular_brdf with "the height-correlated form of the Smith joint
// masking-shadowing function" and V = χ⁺(H·L)χ⁺(H·V) / (2(|N·V|·√(α² + (1 − α²)(N·L)²)
// + |N·L|·√(α² + (1 − α²)(N·V)²))): exactly that, not the separable
// G1·G1 of the conductor (which spec §11 fixes for that material alone).
// Single scattering, no energy compensation, as Appendix B.
#include "render/bsdf_pbr.h"

#include <algorithm>
#include <cmath>

#include "render/brdf.h"
#include "render/bsdf_lobes.h"
#include "render/microfacet.h"

namespace sombra {
namespace {

float mean(Vec3 v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

float pbr_alpha(const Material& m) { return m.roughness * m.roughness; }

// Below kDeltaAlpha the specular part is a delta mirror (as the conductor's).
bool smooth(const Material& m) { return pbr_alpha(m) < kDeltaAlpha; }

// Schlick's Fresnel of the dielectric layer at cos θ as KHR_materials_specular
// defines it: from f0 = min(((1 − ior)/(1 + ior))² · specular_color, 1) ·
// specular to f90 = specular. With the defaults (1, white) it is glTF's core
// Schlick term from f0 = ((1 − ior)/(1 + ior))² to 1, bit for bit.
Vec3 dielectric_fresnel(const Material& m, float cos_theta) {
    const float r = (1.0f - m.ior) / (1.0f + m.ior);
    const Vec3 f0 = min(Vec3{r * r} * m.specular_color, Vec3{1.0f}) * m.specular;
    const float c = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
    const float c2 = c * c;
    return f0 + (Vec3{m.specular} - f0) * (c2 * c2 * c);
}

// The two parts of f (1/sr), both directions local with z > 0: the diffuse
// base under the dielectric layer, and the specular lobe of layer and metal.
// In the smooth case the specular part is a delta and `specular` is 0.
struct PbrParts {
    Vec3 diffuse;
    Vec3 specular;
};

PbrParts eval_parts(const Material& m, Vec3 wo, Vec3 wi) {
    const Vec3 h = normalize(wi + wo);
    const float cos_oh = dot(wo, h);
    const Vec3 fd = dielectric_fresnel(m, cos_oh);
    // The base keeps what the layer's strongest channel leaves (the
    // extension's max_value), so that a coloured layer adds no complementary colour.
    PbrParts parts{m.base_color * ((1.0f - m.metallic) * (1.0f - max_component(fd)) * kInvPi), Vec3{0.0f}};
    if (smooth(m)) return parts;
    const float alpha = pbr_alpha(m);
    const Vec3 fresnel = (1.0f - m.metallic) * fd + m.metallic * fresnel_schlick(m.base_color, cos_oh);
    parts.specular = fresnel * (ggx_v_height_correlated(wo, wi, alpha) * ggx_d(h, alpha));
    return parts;
}

// The Fresnel factor of the specular part (layer and metal) at ωo·h = cos θ_o:
// the smooth mirror's reflectance, and the rough lobe's albedo as lobe
// selection estimates it.
Vec3 specular_reflectance(const Material& m, float cos_o) {
    return (1.0f - m.metallic) * dielectric_fresnel(m, cos_o) + m.metallic * fresnel_schlick(m.base_color, cos_o);
}

// The probability of sampling the specular lobe rather than the cosine one:
// the specular reflectance against the diffuse albedo (1 − m)(1 − F_d)·c, both
// at cos θ_o and averaged over RGB, kept in [0.25, 0.9] so that neither lobe
// is starved (a 4% highlight on plastic would otherwise be found by 4% of the
// samples); 1 when the diffuse part is black (a metal), which needs no cosine lobe.
float specular_probability(const Material& m, float cos_o) {
    const float s = mean(specular_reflectance(m, cos_o));
    const float d = (1.0f - m.metallic) * (1.0f - max_component(dielectric_fresnel(m, cos_o))) * mean(m.base_color);
    if (!(d > 0.0f)) return 1.0f;
    return std::clamp(s / (s + d), 0.25f, 0.9f);
}

}  // namespace

bool is_delta_pbr(const Material& m) { return smooth(m) && m.metallic >= 1.0f; }

Vec3 eval_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    const Vec3 wo_l = p.frame.to_local(wo), wi_l = p.frame.to_local(wi);
    if (wo_l.z <= 0.0f || wi_l.z <= 0.0f) return Vec3{0.0f};
    const PbrParts parts = eval_parts(m, wo_l, wi_l);
    return parts.diffuse + parts.specular;
}

BsdfTerms eval_pbr_terms(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    const Vec3 wo_l = p.frame.to_local(wo), wi_l = p.frame.to_local(wi);
    if (wo_l.z <= 0.0f || wi_l.z <= 0.0f) return {Vec3{0.0f}, Vec3{0.0f}};
    const PbrParts parts = eval_parts(m, wo_l, wi_l);
    return {parts.diffuse, parts.specular};
}

float pdf_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    const Vec3 wo_l = p.frame.to_local(wo), wi_l = p.frame.to_local(wi);
    if (wo_l.z <= 0.0f || wi_l.z <= 0.0f) return 0.0f;
    const float ps = specular_probability(m, wo_l.z);
    const float diffuse = (1.0f - ps) * wi_l.z * kInvPi;
    if (smooth(m)) return diffuse;
    return ps * ggx_reflection_pdf(wo_l, wi_l, pbr_alpha(m)) + diffuse;
}

bool sample_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2, BsdfSample& out) {
    const Vec3 wo_l = p.frame.to_local(wo);
    if (wo_l.z <= 0.0f) return false;
    const float ps = specular_probability(m, wo_l.z);
    Vec3 wi_l;
    if (u_lobe < ps) {
        if (smooth(m)) return sample_specular_reflection(p, wo, specular_reflectance(m, wo_l.z) / ps, ps, out);
        wi_l = reflect(wo_l, sample_ggx_vndf(wo_l, pbr_alpha(m), u1, u2));
        if (wi_l.z <= 0.0f) return false;
    } else {
        wi_l = sample_cosine_hemisphere(u1, u2);
    }
    const Vec3 wi = p.frame.to_world(wi_l);
    if (dot(p.n_g, wi) <= 0.0f) return false;
    // The mixture's density of the world direction, exactly as pdf_bsdf
    // computes it; the weight is then f·cos/pdf with nothing cancelled.
    const float pdf = pdf_pbr(m, p, wo, wi);
    if (!(pdf > 0.0f)) return false;
    out = BsdfSample{wi, eval_pbr(m, p, wo, wi) * (std::fabs(dot(p.n_s, wi)) / pdf), pdf, false, false};
    return max_component(out.weight) > 0.0f && is_finite(out.weight);
}

}  // namespace sombra
