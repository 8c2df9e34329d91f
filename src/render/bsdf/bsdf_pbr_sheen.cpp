// glTF's KHR_materials_sheen over spec §11's `pbr` material (and under its
// clearcoat, render/bsdf/bsdf_pbr_layers.cpp): the extension's albedo-scaling
// layer,
//
//   sheen_material = c_s·f_sheen + base·min(1 − max(c_s)·E(cos θ_o), 1 − max(c_s)·E(cos θ_i))
//
// with c_s = sheen_color, f_sheen the Charlie lobe D·V and E its directional
// albedo (render/bsdf/sheen.h), base the material of render/bsdf/bsdf_pbr.cpp. The
// scaling is clamped at 0: E exceeds 1 at grazing views of smooth sheens.
// Light through the surface (KHR_materials_transmission) crosses the fibres
// on the side of ωo alone: its scaling is 1 − max(c_s)·E(cos θ_o), and so is
// a smooth base's delta mirror's (ωi = ωo mirrored, the same cosine).
//
// Sampling: the sheen lobe, uniform over the hemisphere of n_s (its mass
// lies near the horizon, where a cosine density would starve it), with
// probability P_s = a_s / (a_s + (1 − a_s)·a), a_s = max(c_s)·E(cos θ_o),
// a = mean(base_color), kept in [0.1, 0.9]; else the base with u_lobe
// rescaled. Non-delta samples weigh f·cos/pdf against the whole mixture
// P_s/(2π) + (1 − P_s)·pdf_base.
//
// A material whose sheen colour is black is the base, bit for bit, and
// costs one comparison.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/bsdf/bsdf_lobes.h"
#include "render/bsdf/bsdf_pbr.h"
#include "render/bsdf/sheen.h"

namespace sombra {
namespace {

constexpr float kInvTwoPi = 0.5f * std::numbers::inv_pi_v<float>;

bool sheened(const Material& m) { return max_component(m.sheen_color) > 0.0f; }

// 1 − max(c_s)·E(cos θ), clamped at 0: the fraction of the light crossing
// the fibres at angle θ that they leave to the base.
float sheen_scale(const Material& m, float cos_theta) {
    return std::max(0.0f, 1.0f - max_component(m.sheen_color) * sheen_albedo(cos_theta, m.sheen_roughness));
}

float sheen_probability(const Material& m, float cos_o) {
    const float as = std::min(1.0f, max_component(m.sheen_color) * sheen_albedo(cos_o, m.sheen_roughness));
    const float a = std::max(0.0f, (m.base_color.x + m.base_color.y + m.base_color.z) * (1.0f / 3.0f));
    const float sum = as + (1.0f - as) * a;
    return sum > 0.0f ? std::clamp(as / sum, 0.1f, 0.9f) : 0.9f;
}

}  // namespace

bool is_delta_pbr_sheen(const Material& m) { return !sheened(m) && is_delta_pbr_base(m); }

BsdfTerms eval_pbr_terms_sheen(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    BsdfTerms t = eval_pbr_terms_base(m, p, wo, wi);
    if (!sheened(m)) return t;
    const Vec3 wo_l = p.frame.to_local(wo), wi_l = p.frame.to_local(wi);
    if (wo_l.z <= 0.0f) return {Vec3{0.0f}, Vec3{0.0f}};
    const float scale_o = sheen_scale(m, wo_l.z);
    if (dot(p.n_g, wi) <= 0.0f || wi_l.z <= 0.0f) {
        // Through the surface (or the no-leak rule's zero): ωo's crossing only.
        t.diffuse = t.diffuse * scale_o;
        t.lobe = t.lobe * scale_o;
        t.transmission = t.transmission * scale_o;
        return t;
    }
    const float scale = std::min(scale_o, sheen_scale(m, wi_l.z));
    t.diffuse = t.diffuse * scale;
    t.lobe = t.lobe * scale;
    t.transmission = t.transmission * scale;
    t.sheen = m.sheen_color * eval_sheen_lobe(wo_l, wi_l, m.sheen_roughness);
    return t;
}

Vec3 eval_pbr_sheen(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    if (!sheened(m)) return eval_pbr_base(m, p, wo, wi);
    const BsdfTerms t = eval_pbr_terms_sheen(m, p, wo, wi);
    return t.diffuse + t.lobe + t.transmission + t.sheen;
}

float pdf_pbr_sheen(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    if (!sheened(m)) return pdf_pbr_base(m, p, wo, wi);
    const Vec3 wo_l = p.frame.to_local(wo), wi_l = p.frame.to_local(wi);
    if (wo_l.z <= 0.0f) return 0.0f;
    const float ps = sheen_probability(m, wo_l.z);
    float pdf = (1.0f - ps) * pdf_pbr_base(m, p, wo, wi);
    if (dot(p.n_g, wi) > 0.0f && wi_l.z > 0.0f) pdf += ps * kInvTwoPi;
    return pdf;
}

bool sample_pbr_sheen(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2,
                      BsdfSample& out) {
    if (!sheened(m)) return sample_pbr_base(m, p, wo, u_lobe, u1, u2, out);
    const Vec3 wo_l = p.frame.to_local(wo);
    if (wo_l.z <= 0.0f) return false;
    const float ps = sheen_probability(m, wo_l.z);
    Vec3 wi;
    if (u_lobe < ps) {
        wi = p.frame.to_world(sample_uniform_hemisphere(u1, u2));
        if (dot(p.n_g, wi) <= 0.0f) return false;
    } else {
        const float u_base = std::min((u_lobe - ps) / (1.0f - ps), 0x1.fffffep-1f);
        if (!sample_pbr_base(m, p, wo, u_base, u1, u2, out)) return false;
        if (out.delta) {
            out.weight = out.weight * (sheen_scale(m, wo_l.z) / (1.0f - ps));
            out.pdf *= 1.0f - ps;
            return max_component(out.weight) > 0.0f;
        }
        wi = out.wi;
    }
    // The whole mixture's density, and f·cos/pdf with nothing cancelled.
    const float pdf = pdf_pbr_sheen(m, p, wo, wi);
    if (!(pdf > 0.0f)) return false;
    out = BsdfSample{wi, eval_pbr_sheen(m, p, wo, wi) * (std::fabs(dot(p.n_s, wi)) / pdf), pdf, false,
                     dot(p.n_g, wi) < 0.0f};
    return max_component(out.weight) > 0.0f && is_finite(out.weight);
}

}  // namespace sombra
