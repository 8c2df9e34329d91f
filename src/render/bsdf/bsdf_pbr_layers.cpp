// glTF's KHR_materials_clearcoat over spec §11's `pbr` material: a GGX
// dielectric coat of ior 1.5 (f0 = 0.04) layered as the extension says,
//
//   coated = fresnel_coat(ior = 1.5, weight = k, base = material, layer = clearcoat_brdf)
//          = (1 − k·F_c(n·ωo))·base + k·F_c(n·ωo)·V(α_c)·D(α_c)
//
// with k = clearcoat, base the material under the coat (with its sheen,
// render/bsdf/bsdf_pbr_sheen.cpp: the extension puts the coat on top), F_c
// Schlick from 0.04 at the view's cos θ_o (the
// extension's NdotV, not ωo·h), clearcoat_brdf the core specular_brdf
// (height-correlated V, GGX D) at α_c = clearcoat_roughness². The coat does
// not transmit: light through the base (KHR_materials_transmission) is
// weighted by 1 − k·F_c alone. Below kDeltaAlpha the coat is a delta
// mirror of weight k·F_c.
//
// The coat's normal n_c (BsdfPoint::n_c: its clearcoatNormalTexture, or
// the surface's normal without the base's maps) may differ from the base's
// n_s. F_c, V and D then read directions in a frame around n_c, and since
// the integrators multiply f by |n_s·ωi|, the coat's term is stored as
// k·F_c·V·D·(n_c·ωi)/|n_s·ωi|, so that f·cos is the extension's
// k·F_c·V·D·(n_c·ωi) (and a smooth coat is the mirror about n_c of weight
// k·F_c, its limit). The coat needs n_c·ωo > 0 and n_c·ωi > 0, the base
// its own n_s conditions; at n_c·ωo ≤ 0 F_c is 1 (Schlick at cos 0). With
// n_c zero (no map on either layer) it is all p.frame's, bit for bit as
// before.
//
// Sampling: the coat with probability P_c = k·F_c / (k·F_c + (1 − k·F_c)·a),
// a = mean(base_color) (the base's albedo as far as the choice needs it),
// kept in [0.1, 0.9]; else the base (render/bsdf/bsdf_pbr_sheen.cpp) with u_lobe
// rescaled. Non-delta samples weigh f·cos/pdf against the whole mixture
// P_c·pdf_coat + (1 − P_c)·pdf_base.
#include <algorithm>
#include <cmath>

#include "render/bsdf/bsdf_lobes.h"
#include "render/bsdf/bsdf_pbr.h"
#include "render/bsdf/microfacet.h"

namespace sombra {
namespace {

bool coated(const Material& m) { return m.clearcoat > 0.0f; }

float coat_alpha(const Material& m) { return m.clearcoat_roughness * m.clearcoat_roughness; }

bool smooth_coat(const Material& m) { return coat_alpha(m) < kDeltaAlpha; }

// k·F_c(cos θ_o): the coat's share of the light, Schlick from f0 = 0.04 (ior 1.5).
float coat_blend(const Material& m, float cos_o) {
    constexpr float f0 = 0.04f;
    const float c = 1.0f - std::clamp(cos_o, 0.0f, 1.0f);
    const float c2 = c * c;
    return m.clearcoat * (f0 + (1.0f - f0) * (c2 * c2 * c));
}

float coat_probability(const Material& m, float blend) {
    const float a = std::max(0.0f, (m.base_color.x + m.base_color.y + m.base_color.z) * (1.0f / 3.0f));
    return std::clamp(blend / (blend + (1.0f - blend) * a), 0.1f, 0.9f);
}

// The coat's lobe V·D (1/sr) for local directions above the surface; 0 when smooth.
float coat_lobe(const Material& m, Vec3 wo_l, Vec3 wi_l) {
    if (smooth_coat(m) || wo_l.z <= 0.0f || wi_l.z <= 0.0f) return 0.0f;
    const float alpha = coat_alpha(m);
    return ggx_v_height_correlated(wo_l, wi_l, alpha) * ggx_d(normalize(wi_l + wo_l), alpha);
}

// The coat's shading frame: p.frame itself unless the coat has its own
// normal (`own`), which costs one frame only at coated points that have one.
struct CoatFrame {
    Frame frame;
    bool own;
};

CoatFrame coat_frame(const BsdfPoint& p) {
    if (p.n_c == Vec3{}) return {p.frame, false};
    return {Frame::from_normal(p.n_c), true};
}

// The factor (n_c·ωi)/|n_s·ωi| of an own coat normal's term (the header
// above); 0 where n_s·ωi is 0, where the integrators' cosine zeroes it anyway.
float coat_cos_ratio(const BsdfPoint& p, float cos_c, Vec3 wi) {
    const float cos_s = std::fabs(dot(p.n_s, wi));
    return cos_s > 0.0f ? cos_c / cos_s : 0.0f;
}

}  // namespace

bool is_delta_pbr(const Material& m) { return is_delta_pbr_sheen(m) && (!coated(m) || smooth_coat(m)); }

BsdfTerms eval_pbr_terms(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    BsdfTerms t = eval_pbr_terms_sheen(m, p, wo, wi);
    if (!coated(m)) return t;
    const CoatFrame c = coat_frame(p);
    const Vec3 wo_l = c.frame.to_local(wo), wi_l = c.frame.to_local(wi);
    if (!c.own && wo_l.z <= 0.0f) return {Vec3{0.0f}, Vec3{0.0f}};
    const float blend = coat_blend(m, wo_l.z);
    const float under = 1.0f - blend;
    const bool above = dot(p.n_g, wi) > 0.0f;
    float coat = above ? blend * coat_lobe(m, wo_l, wi_l) : 0.0f;
    if (c.own && coat > 0.0f) coat *= coat_cos_ratio(p, wi_l.z, wi);
    return {t.diffuse * under, t.lobe * under, t.transmission * under, Vec3{coat}, t.sheen * under};
}

Vec3 eval_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    if (!coated(m)) return eval_pbr_sheen(m, p, wo, wi);
    const BsdfTerms t = eval_pbr_terms(m, p, wo, wi);
    return t.diffuse + t.lobe + t.transmission + t.coat + t.sheen;
}

float pdf_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    if (!coated(m)) return pdf_pbr_sheen(m, p, wo, wi);
    const CoatFrame c = coat_frame(p);
    const Vec3 wo_l = c.frame.to_local(wo), wi_l = c.frame.to_local(wi);
    if (!c.own && wo_l.z <= 0.0f) return 0.0f;
    const float pc = coat_probability(m, coat_blend(m, wo_l.z));
    float pdf = (1.0f - pc) * pdf_pbr_sheen(m, p, wo, wi);
    // ggx_reflection_pdf is 0 unless both are above n_c, where sampling fails.
    if (!smooth_coat(m) && dot(p.n_g, wi) > 0.0f) pdf += pc * ggx_reflection_pdf(wo_l, wi_l, coat_alpha(m));
    return pdf;
}

bool sample_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2, BsdfSample& out) {
    if (!coated(m)) return sample_pbr_sheen(m, p, wo, u_lobe, u1, u2, out);
    const CoatFrame c = coat_frame(p);
    const Vec3 wo_l = c.frame.to_local(wo);
    if (!c.own && wo_l.z <= 0.0f) return false;
    const float blend = coat_blend(m, wo_l.z);
    const float pc = coat_probability(m, blend);
    Vec3 wi;
    if (u_lobe < pc) {
        if (wo_l.z <= 0.0f) return false;
        if (smooth_coat(m)) {
            if (!c.own) return sample_specular_reflection(p, wo, Vec3{blend / pc}, pc, out);
            wi = reflect(wo, p.n_c);
            if (dot(p.n_g, wi) <= 0.0f || !(blend > 0.0f)) return false;
            out = BsdfSample{wi, Vec3{blend / pc}, pc, true, false};
            return true;
        }
        const Vec3 wi_l = reflect(wo_l, sample_ggx_vndf(wo_l, coat_alpha(m), u1, u2));
        if (wi_l.z <= 0.0f) return false;
        wi = c.frame.to_world(wi_l);
        if (dot(p.n_g, wi) <= 0.0f) return false;
    } else {
        const float u_base = std::min((u_lobe - pc) / (1.0f - pc), 0x1.fffffep-1f);
        if (!sample_pbr_sheen(m, p, wo, u_base, u1, u2, out)) return false;
        if (out.delta) {
            out.weight = out.weight * ((1.0f - blend) / (1.0f - pc));
            out.pdf *= 1.0f - pc;
            return max_component(out.weight) > 0.0f;
        }
        wi = out.wi;
    }
    // The whole mixture's density, and f·cos/pdf with nothing cancelled.
    const float pdf = pdf_pbr(m, p, wo, wi);
    if (!(pdf > 0.0f)) return false;
    out = BsdfSample{wi, eval_pbr(m, p, wo, wi) * (std::fabs(dot(p.n_s, wi)) / pdf), pdf, false, dot(p.n_g, wi) < 0.0f};
    return max_component(out.weight) > 0.0f && is_finite(out.weight);
}

}  // namespace sombra
