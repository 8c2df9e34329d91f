// Spec §11's `pbr`: the glTF 2.0 metallic–roughness BRDF of the glTF
// specification's Appendix B, in its mix form,
//
//   f = (1 − m)·fresnel_mix(ior, diffuse_brdf(c), specular_brdf(α)) + m·conductor_fresnel(c, specular_brdf(α))
//     = (1 − m)(1 − max(F_d))·c/π  +  ((1 − m)·F_d + m·F_c)·V·D     ("diffuse" + "specular" below)
//
// with c = base_color, m = metallic, α = roughness², D the GGX distribution
// (render/bsdf/microfacet.h), F_d = Schlick with f0 = ((1 − ior)/(1 + ior))² and
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
//
// glTF's KHR_materials_transmission replaces the diffuse base by
// mix(diffuse, specular_btdf·c, t), t = transmission, under the same
// Fresnel layer: the light that the layer lets in (1 − max(F_d)) goes
// through the surface with probability t, tinted by c; metals transmit
// nothing. On a thin wall (KHR_materials_volume's thickness 0) the surface
// is two back-to-back interfaces that do not bend the ray: smooth, ωi = −ωo
// (a delta); rough, the extension's microfacet BTDF V_T·D_T at the
// transmission half vector H_T = normalize(ωo + ωi'), ωi' = ωi mirrored
// through the surface plane, V_T the separable Smith form of its
// implementation notes, i.e. the reflection lobe's geometry mirrored to the
// back. With a volume (thickness > 0, ior > 1) the transmission refracts by
// Snell's law at the material's ior, with the dielectric material's
// radiance scaling (η_i/η_t)²; from inside, the layer's Fresnel is 1 beyond
// the critical angle and Schlick's at the outer angle cos θ_t otherwise
// (layer_fresnel). Smooth, that is a delta; rough, it is Walter et al.'s
// microfacet BTDF (render/bsdf/microfacet_refraction.h), the frosted glass of
// Cycles and the Khronos viewer,
//
//   f_t = (1 − m)·t·c·(1 − max(F_d(ωo·h))) · |ωi·h| (ωo·h) / (|cos θ_i| cos θ_o)
//         · η² G1(ωo) G1(ωi) D(h) / (ωi·h + η ωo·h)²,
//
// h the generalized half vector, η = η_o/η_t (ωo's side over ωi's), G the
// separable Smith form of the thin wall's V_T. The η² is the same radiance
// scaling as the smooth refraction's: a sampled refraction weighs
// η²·(1 − F)·G1(ωi)/P, which tends to the delta's weight as α → 0. Its
// reflection counterpart is the rough lobe above, unchanged. Both are
// sampled from one visible normal h, which reflects or refracts with
// probability in proportion to their Fresnel weights at ωo·h
// (reflect_probability): by Fresnel for white glass.
#include "render/bsdf/bsdf_pbr.h"

#include <algorithm>
#include <cmath>

#include "render/bsdf/brdf.h"
#include "render/bsdf/bsdf_lobes.h"
#include "render/bsdf/microfacet.h"
#include "render/bsdf/microfacet_refraction.h"

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

// The volume's interfaces refract: KHR_materials_volume's closed mesh of ior > 1.
bool refracts(const Material& m) { return m.transmission > 0.0f && m.thickness > 0.0f && m.ior > 1.0f; }

// The layer's Fresnel at cos θ (of ωo against n_s or h) for ωo on the side
// `inside` (BsdfPoint::outside false): dielectric_fresnel, except inside a
// refracting volume, where light meets the interface from the denser side:
// 1 (total internal reflection) beyond the critical angle, else Schlick's
// at the angle on the outer side, so that both sides of an interface agree
// on how much of the light crosses it.
Vec3 layer_fresnel(const Material& m, bool inside, float cos_theta) {
    if (inside && refracts(m)) {
        const float c = std::clamp(cos_theta, 0.0f, 1.0f);
        const float sin2_t = m.ior * m.ior * (1.0f - c * c);
        if (sin2_t >= 1.0f) return Vec3{1.0f};
        cos_theta = std::sqrt(1.0f - sin2_t);
    }
    return dielectric_fresnel(m, cos_theta);
}

// The two parts of f (1/sr), both directions local with z > 0: the diffuse
// base under the dielectric layer, and the specular lobe of layer and metal.
// In the smooth case the specular part is a delta and `specular` is 0.
struct PbrParts {
    Vec3 diffuse;
    Vec3 specular;
};

PbrParts eval_parts(const Material& m, bool inside, Vec3 wo, Vec3 wi) {
    const Vec3 h = normalize(wi + wo);
    const float cos_oh = dot(wo, h);
    const Vec3 fd = layer_fresnel(m, inside, cos_oh);
    // The base keeps what the layer's strongest channel leaves (the
    // extension's max_value), so that a coloured layer adds no complementary
    // colour; the transmitted fraction of it is not diffuse.
    PbrParts parts{m.base_color * ((1.0f - m.metallic) * (1.0f - max_component(fd)) * kInvPi * (1.0f - m.transmission)),
                   Vec3{0.0f}};
    if (smooth(m)) return parts;
    const float alpha = pbr_alpha(m);
    const Vec3 fresnel = (1.0f - m.metallic) * fd + m.metallic * fresnel_schlick(m.base_color, cos_oh);
    parts.specular = fresnel * (ggx_v_height_correlated(wo, wi, alpha) * ggx_d(h, alpha));
    return parts;
}

// The thin wall's rough transmission f (1/sr), wo.z > 0 > wi.z, local:
// (1 − m)·t·(1 − max(F_d))·c · V_T·D_T at H_T (the header above).
Vec3 eval_thin_transmission(const Material& m, Vec3 wo, Vec3 wi) {
    const Vec3 wr{wi.x, wi.y, -wi.z};
    const Vec3 h = normalize(wo + wr);
    const float alpha = pbr_alpha(m);
    const float btdf = 0.25f * ggx_d(h, alpha) * ggx_g1_over_cos(wr, alpha) * ggx_g1_over_cos(wo, alpha);
    const float fd = max_component(dielectric_fresnel(m, dot(wo, h)));
    return m.base_color * ((1.0f - m.metallic) * m.transmission * (1.0f - fd) * btdf);
}

// η_o/η_t for ωo on the side `inside`: 1/ior entering the volume, ior leaving it.
float refraction_eta(const Material& m, bool inside) { return inside ? m.ior : 1.0f / m.ior; }

// The volume's rough transmission f (1/sr), wo.z > 0 > wi.z, local: f_t of
// the header above; 0 for a pair that no facet facing both refracts into
// each other.
Vec3 eval_rough_refraction(const Material& m, bool inside, Vec3 wo, Vec3 wi) {
    const float eta = refraction_eta(m, inside);
    const Vec3 h = refraction_half_vector(wo, wi, eta);
    const float cos_oh = dot(wo, h);
    if (!(cos_oh > 0.0f) || !(dot(wi, h) < 0.0f)) return Vec3{0.0f};
    const float alpha = pbr_alpha(m);
    // ggx_g1_over_cos carries the 1/|cos θ| of both directions.
    const float btdf = eta * eta * refraction_jacobian(wo, wi, h, eta) * cos_oh * ggx_d(h, alpha) *
                       ggx_g1_over_cos(wo, alpha) * ggx_g1_over_cos(wi, alpha);
    // layer_fresnel's Schlick term at the outer angle, read off the outer
    // direction: its Snell conversion from inside loses (1 − F)'s digits
    // near the critical angle (percents there), and the two sides of a
    // facet would then disagree on what crosses it.
    const float fd = max_component(dielectric_fresnel(m, inside ? -dot(wi, h) : cos_oh));
    return m.base_color * ((1.0f - m.metallic) * m.transmission * (1.0f - fd) * btdf);
}

// The rough transmission through the surface, wo.z > 0 > wi.z, local:
// refracted into (or out of) a volume, else the thin wall's.
Vec3 eval_rough_transmission(const Material& m, bool inside, Vec3 wo, Vec3 wi) {
    return refracts(m) ? eval_rough_refraction(m, inside, wo, wi) : eval_thin_transmission(m, wo, wi);
}

// The Fresnel factor of the specular part (layer and metal) at ωo·h = cos θ_o:
// the smooth mirror's reflectance, and the rough lobe's albedo as lobe
// selection estimates it.
Vec3 specular_reflectance(const Material& m, bool inside, float cos_o) {
    return (1.0f - m.metallic) * layer_fresnel(m, inside, cos_o) + m.metallic * fresnel_schlick(m.base_color, cos_o);
}

// The probability of sampling the specular lobe rather than the cosine one:
// the specular reflectance against the diffuse albedo (1 − m)(1 − F_d)·c, both
// at cos θ_o and averaged over RGB, kept in [0.25, 0.9] so that neither lobe
// is starved (a 4% highlight on plastic would otherwise be found by 4% of the
// samples); 1 when the diffuse part is black (a metal), which needs no cosine lobe.
float specular_probability(const Material& m, bool inside, float cos_o) {
    const float s = mean(specular_reflectance(m, inside, cos_o));
    const float d = (1.0f - m.metallic) * (1.0f - max_component(layer_fresnel(m, inside, cos_o))) * mean(m.base_color);
    if (!(d > 0.0f)) return 1.0f;
    return std::clamp(s / (s + d), 0.25f, 0.9f);
}

// The probability of the transmission lobe: its share t of the base's 1 − P_s.
float transmission_probability(const Material& m, float ps) {
    return m.transmission > 0.0f ? (1.0f - ps) * m.transmission : 0.0f;
}

// A rough volume's interface (transmits_diffusely and refracts) draws
// reflection and refraction from one visible normal, as one lobe chosen
// with probability P_s + P_t.
bool rough_refraction(const Material& m) { return refracts(m) && transmits_diffusely(m); }

// The probability that a visible normal h drawn for a rough volume's
// interface reflects ωo rather than refracting it: the reflection's Fresnel
// weight against the transmission's, both at ωo·h = cos_oh and averaged
// over RGB (as specular_probability's); 1 when nothing is transmitted
// (beyond the critical angle, or a black base colour).
float reflect_probability(const Material& m, bool inside, float cos_oh) {
    const Vec3 fd = layer_fresnel(m, inside, cos_oh);
    const float s = mean((1.0f - m.metallic) * fd + m.metallic * fresnel_schlick(m.base_color, cos_oh));
    const float t = (1.0f - m.metallic) * m.transmission * (1.0f - max_component(fd)) * mean(m.base_color);
    return t > 0.0f ? s / (s + t) : 1.0f;
}

// The density (1/sr) with which a rough volume's interface lobe, chosen
// with probability pm, draws wi (local; wo.z > 0): reflected, D_ωo(h)/(4 ωo·h)
// at h = normalize(ωo + ωi); refracted, D_ωo(h)·|∂ω_h/∂ω_i| at the
// generalized half vector; each times its share reflect_probability.
float rough_interface_pdf(const Material& m, bool inside, Vec3 wo, Vec3 wi, float pm) {
    const float alpha = pbr_alpha(m);
    if (wi.z > 0.0f) {
        const float pdf = ggx_reflection_pdf(wo, wi, alpha);
        return pm * reflect_probability(m, inside, dot(wo, normalize(wi + wo))) * pdf;
    }
    const float eta = refraction_eta(m, inside);
    const Vec3 h = refraction_half_vector(wo, wi, eta);
    const float cos_oh = dot(wo, h);
    if (!(cos_oh > 0.0f) || !(dot(wi, h) < 0.0f)) return 0.0f;
    // D_ωo(h) = G1(ωo)·(ωo·h)·D(h)/cos θ_o, Heitz's density of visible normals.
    const float visible = ggx_g1_over_cos(wo, alpha) * cos_oh * ggx_d(h, alpha);
    return pm * (1.0f - reflect_probability(m, inside, cos_oh)) * visible * refraction_jacobian(wo, wi, h, eta);
}

// Draws wi (local) from a rough volume's interface: a visible normal h, then
// reflection about it if u (in [0, 1)) < reflect_probability, else
// refraction. False when wi lands on the wrong side of the surface.
bool sample_rough_interface(const Material& m, bool inside, Vec3 wo, float u, float u1, float u2, Vec3& wi) {
    const Vec3 h = sample_ggx_vndf(wo, pbr_alpha(m), u1, u2);
    if (u < reflect_probability(m, inside, dot(wo, h))) {
        wi = reflect(wo, h);
        return wi.z > 0.0f;
    }
    return refract_about(wo, h, refraction_eta(m, inside), wi) && wi.z < 0.0f;
}

// The delta transmission (smooth thin wall, or a volume's refraction),
// chosen with probability pt; cos_o = ωo·n_s > 0.
bool sample_delta_transmission(const Material& m, const BsdfPoint& p, Vec3 wo, float cos_o, float pt, BsdfSample& out) {
    const float fd = max_component(layer_fresnel(m, !p.outside, cos_o));
    Vec3 weight = m.base_color * ((1.0f - m.metallic) * m.transmission * (1.0f - fd) / pt);
    Vec3 wi = -wo;
    if (refracts(m)) {
        // Snell, as the dielectric material: ωt = −η ωo + (η cos_i − cos_t) n_s, η = η_i/η_t.
        const float eta = p.outside ? 1.0f / m.ior : m.ior;
        const float sin2_t = eta * eta * std::max(0.0f, 1.0f - cos_o * cos_o);
        if (sin2_t >= 1.0f) return false;
        const float cos_t = std::sqrt(1.0f - sin2_t);
        wi = normalize(-eta * wo + (eta * cos_o - cos_t) * p.n_s);
        weight = weight * (eta * eta);
    }
    if (dot(p.n_g, wi) >= 0.0f || !(max_component(weight) > 0.0f)) return false;
    out = BsdfSample{wi, weight, pt, true, true};
    return true;
}

}  // namespace

bool is_delta_pbr_base(const Material& m) { return smooth(m) && (m.metallic >= 1.0f || m.transmission >= 1.0f); }

float pbr_transmission_eta_scale(const Material& m, bool outside) {
    if (!refracts(m)) return 1.0f;
    return outside ? m.ior * m.ior : 1.0f / (m.ior * m.ior);
}

BsdfTerms eval_pbr_terms_base(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    const Vec3 wo_l = p.frame.to_local(wo), wi_l = p.frame.to_local(wi);
    if (wo_l.z <= 0.0f) return {Vec3{0.0f}, Vec3{0.0f}};
    if (dot(p.n_g, wi) <= 0.0f) {
        if (wi_l.z >= 0.0f || !transmits_diffusely(m)) return {Vec3{0.0f}, Vec3{0.0f}};
        return {Vec3{0.0f}, Vec3{0.0f}, eval_rough_transmission(m, !p.outside, wo_l, wi_l)};
    }
    if (wi_l.z <= 0.0f) return {Vec3{0.0f}, Vec3{0.0f}};
    const PbrParts parts = eval_parts(m, !p.outside, wo_l, wi_l);
    return {parts.diffuse, parts.specular};
}

Vec3 eval_pbr_base(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    const Vec3 wo_l = p.frame.to_local(wo), wi_l = p.frame.to_local(wi);
    if (dot(p.n_g, wi) <= 0.0f) {
        if (wo_l.z <= 0.0f || wi_l.z >= 0.0f || !transmits_diffusely(m)) return Vec3{0.0f};
        return eval_rough_transmission(m, !p.outside, wo_l, wi_l);
    }
    if (wo_l.z <= 0.0f || wi_l.z <= 0.0f) return Vec3{0.0f};
    const PbrParts parts = eval_parts(m, !p.outside, wo_l, wi_l);
    return parts.diffuse + parts.specular;
}

float pdf_pbr_base(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    const Vec3 wo_l = p.frame.to_local(wo), wi_l = p.frame.to_local(wi);
    if (wo_l.z <= 0.0f) return 0.0f;
    const bool inside = !p.outside;
    const float ps = specular_probability(m, inside, wo_l.z);
    const float pt = transmission_probability(m, ps);
    if (dot(p.n_g, wi) <= 0.0f) {
        if (wi_l.z >= 0.0f || !transmits_diffusely(m)) return 0.0f;
        if (refracts(m)) return rough_interface_pdf(m, inside, wo_l, wi_l, ps + pt);
        const Vec3 wr{wi_l.x, wi_l.y, -wi_l.z};
        return pt * ggx_reflection_pdf(wo_l, wr, pbr_alpha(m));
    }
    if (wi_l.z <= 0.0f) return 0.0f;
    const float diffuse = (1.0f - ps) * (1.0f - m.transmission) * wi_l.z * kInvPi;
    if (smooth(m)) return diffuse;
    if (rough_refraction(m)) return rough_interface_pdf(m, inside, wo_l, wi_l, ps + pt) + diffuse;
    return ps * ggx_reflection_pdf(wo_l, wi_l, pbr_alpha(m)) + diffuse;
}

bool sample_pbr_base(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2,
                     BsdfSample& out) {
    const Vec3 wo_l = p.frame.to_local(wo);
    if (wo_l.z <= 0.0f) return false;
    const bool inside = !p.outside;
    const float ps = specular_probability(m, inside, wo_l.z);
    const float pt = transmission_probability(m, ps);
    Vec3 wi_l;
    if (rough_refraction(m)) {
        const float pm = ps + pt;
        if (u_lobe < pm) {
            if (!sample_rough_interface(m, inside, wo_l, u_lobe / pm, u1, u2, wi_l)) return false;
        } else {
            wi_l = sample_cosine_hemisphere(u1, u2);
        }
    } else if (u_lobe < ps) {
        if (smooth(m)) return sample_specular_reflection(p, wo, specular_reflectance(m, inside, wo_l.z) / ps, ps, out);
        wi_l = reflect(wo_l, sample_ggx_vndf(wo_l, pbr_alpha(m), u1, u2));
        if (wi_l.z <= 0.0f) return false;
    } else if (u_lobe >= 1.0f - pt) {
        if (!transmits_diffusely(m)) return sample_delta_transmission(m, p, wo, wo_l.z, pt, out);
        const Vec3 wr = reflect(wo_l, sample_ggx_vndf(wo_l, pbr_alpha(m), u1, u2));
        if (wr.z <= 0.0f) return false;
        wi_l = Vec3{wr.x, wr.y, -wr.z};
    } else {
        wi_l = sample_cosine_hemisphere(u1, u2);
    }
    const Vec3 wi = p.frame.to_world(wi_l);
    if ((dot(p.n_g, wi) <= 0.0f) != (wi_l.z < 0.0f)) return false;
    // The mixture's density of the world direction, exactly as pdf_bsdf
    // computes it; the weight is then f·cos/pdf with nothing cancelled.
    const float pdf = pdf_pbr_base(m, p, wo, wi);
    if (!(pdf > 0.0f)) return false;
    out = BsdfSample{wi, eval_pbr_base(m, p, wo, wi) * (std::fabs(dot(p.n_s, wi)) / pdf), pdf, false, wi_l.z < 0.0f};
    return max_component(out.weight) > 0.0f && is_finite(out.weight);
}

}  // namespace sombra
