#include "render/bsdf/bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/bsdf/brdf.h"
#include "render/bsdf/bsdf_lobes.h"
#include "render/bsdf/bsdf_pbr.h"
#include "render/bsdf/microfacet.h"

namespace sombra {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float mean(Vec3 v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

float conductor_alpha(const Material& m) { return m.roughness * m.roughness; }

// --- Phong ------------------------------------------------------------------

// Probability of sampling the cosine (diffuse) lobe; 0 and 1 at the extremes,
// 0.5 for a black material (which never samples anything).
float phong_diffuse_probability(const Material& m) {
    const float d = std::max(0.0f, mean(m.kd));
    const float s = std::max(0.0f, mean(m.ks));
    return d + s > 0.0f ? d / (d + s) : 0.5f;
}

// (n+1)/(2π)·max(0, c)^n for c = ωi·r_o; 0 for c ≤ 0, so n = 0 is a uniform
// hemisphere around r_o.
float phong_lobe_pdf(float cos_alpha, float n) {
    if (cos_alpha <= 0.0f) return 0.0f;
    return (n + 1.0f) * (0.5f / kPi) * std::pow(cos_alpha, n);
}

float pdf_phong(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    const float pd = m.type == MaterialType::Phong ? phong_diffuse_probability(m) : 1.0f;
    float pdf = pd * std::max(0.0f, dot(p.n_s, wi)) / kPi;
    if (pd < 1.0f) {
        const Vec3 r_o = normalize(reflect(wo, p.n_s));
        pdf += (1.0f - pd) * phong_lobe_pdf(dot(wi, r_o), m.shininess);
    }
    return pdf;
}

// Diffuse and Phong: their f is eval_brdf's, the weight f·|cos|/pdf.
bool sample_phong(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2, BsdfSample& out) {
    const float pd = m.type == MaterialType::Phong ? phong_diffuse_probability(m) : 1.0f;
    Vec3 wi;
    if (u_lobe < pd) {
        wi = p.frame.to_world(sample_cosine_hemisphere(u1, u2));
    } else {
        const Vec3 r_o = normalize(reflect(wo, p.n_s));
        const float cos_a = std::pow(1.0f - u1, 1.0f / (m.shininess + 1.0f));  // in (0, 1]
        const float sin_a = std::sqrt(std::max(0.0f, 1.0f - cos_a * cos_a));
        const float phi = 2.0f * kPi * u2;
        wi = Frame::from_normal(r_o).to_world({sin_a * std::cos(phi), sin_a * std::sin(phi), cos_a});
    }
    if (dot(p.n_g, wi) <= 0.0f) return false;
    const float pdf = pdf_phong(m, p, wo, wi);
    if (!(pdf > 0.0f)) return false;
    const Vec3 f = eval_brdf(m, p.n_s, wi, wo);
    out.wi = wi;
    out.pdf = pdf;
    out.weight = m.type == MaterialType::Diffuse ? m.kd : f * (std::fabs(dot(p.n_s, wi)) / pdf);
    out.delta = false;
    out.transmission = false;
    return max_component(out.weight) > 0.0f;
}

// --- Conductor --------------------------------------------------------------

// f of the rough conductor, both directions local (z = cos θ); 0 unless both
// are above the shading plane.
Vec3 eval_ggx(Vec3 ks, float alpha, Vec3 wo, Vec3 wi) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return Vec3{0.0f};
    const Vec3 h = normalize(wi + wo);
    const Vec3 F = fresnel_schlick(ks, dot(wo, h));
    const float g = ggx_g1_over_cos(wi, alpha) * ggx_g1_over_cos(wo, alpha);
    return F * (0.25f * ggx_d(h, alpha) * g);
}

// --- Delta lobes ------------------------------------------------------------

bool sample_dielectric(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, BsdfSample& out) {
    const float cos_i = dot(wo, p.n_s);
    if (cos_i <= 0.0f) return false;
    const float eta_i = p.outside ? 1.0f : m.ior;
    const float eta_t = p.outside ? m.ior : 1.0f;
    const float F = fresnel_dielectric(cos_i, eta_i, eta_t);
    if (u_lobe < F) return sample_specular_reflection(p, wo, Vec3{1.0f}, F, out);
    // Snell: ωt = −η ωo + (η cos_i − cos_t) n_s with η = η_i/η_t; F < 1 means no TIR.
    const float eta = eta_i / eta_t;
    const float sin2_t = eta * eta * std::max(0.0f, 1.0f - cos_i * cos_i);
    const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
    const Vec3 wi = normalize(-eta * wo + (eta * cos_i - cos_t) * p.n_s);
    if (dot(p.n_g, wi) >= 0.0f) return false;
    const Vec3 weight = m.kt * (eta * eta);
    if (!(max_component(weight) > 0.0f)) return false;
    out = BsdfSample{wi, weight, 1.0f - F, true, true};
    return true;
}

}  // namespace

BsdfPoint make_bsdf_point(Vec3 n_g, Vec3 n_s, bool outside, Vec3 n_c) {
    return BsdfPoint{n_g, n_s, Frame::from_normal(n_s), outside, n_c};
}

bool is_delta_bsdf(const Material& m) {
    switch (m.type) {
        case MaterialType::Mirror:
        case MaterialType::Dielectric:
        case MaterialType::Interface: return true;
        case MaterialType::Conductor: return conductor_alpha(m) < kDeltaAlpha;
        case MaterialType::Pbr: return is_delta_pbr(m);
        case MaterialType::Diffuse:
        case MaterialType::Phong: return false;
    }
    return false;
}

float transmission_eta_scale(const Material& m, bool outside) {
    if (m.type == MaterialType::Dielectric) return outside ? m.ior * m.ior : 1.0f / (m.ior * m.ior);
    if (m.type == MaterialType::Pbr) return pbr_transmission_eta_scale(m, outside);
    return 1.0f;
}

float fresnel_dielectric(float cos_i, float eta_i, float eta_t) {
    cos_i = std::clamp(cos_i, 0.0f, 1.0f);
    const float eta = eta_i / eta_t;
    const float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
    if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
    const float cos_t = std::sqrt(1.0f - sin2_t);
    const float rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    const float rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    return std::min(1.0f, 0.5f * (rs * rs + rp * rp));
}

Vec3 eval_bsdf_other(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    switch (m.type) {
        case MaterialType::Diffuse:
        case MaterialType::Phong: return eval_brdf(m, p.n_s, wi, wo);
        case MaterialType::Conductor: {
            const float alpha = conductor_alpha(m);
            if (alpha < kDeltaAlpha) return Vec3{0.0f};
            return eval_ggx(m.ks, alpha, p.frame.to_local(wo), p.frame.to_local(wi));
        }
        case MaterialType::Pbr: return eval_pbr(m, p, wo, wi);
        case MaterialType::Mirror:
        case MaterialType::Dielectric:
        case MaterialType::Interface: return Vec3{0.0f};
    }
    return Vec3{0.0f};
}

BsdfTerms eval_bsdf_terms(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    if (dot(p.n_g, wi) <= 0.0f)
        return transmits_diffusely(m) ? eval_pbr_terms(m, p, wo, wi) : BsdfTerms{Vec3{0.0f}, Vec3{0.0f}};
    switch (m.type) {
        case MaterialType::Diffuse: return {eval_lambert(m.kd), Vec3{0.0f}};
        case MaterialType::Phong: return {eval_lambert(m.kd), m.ks * eval_phong_lobe(p.n_s, wi, wo, m.shininess)};
        case MaterialType::Conductor: return {Vec3{0.0f}, eval_bsdf(m, p, wo, wi)};
        case MaterialType::Pbr: return eval_pbr_terms(m, p, wo, wi);
        case MaterialType::Mirror:
        case MaterialType::Dielectric:
        case MaterialType::Interface: return {Vec3{0.0f}, Vec3{0.0f}};
    }
    return {Vec3{0.0f}, Vec3{0.0f}};
}

float pdf_bsdf(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi) {
    if (dot(p.n_g, wi) <= 0.0f) return transmits_diffusely(m) ? pdf_pbr(m, p, wo, wi) : 0.0f;
    switch (m.type) {
        case MaterialType::Diffuse:
        case MaterialType::Phong: return pdf_phong(m, p, wo, wi);
        case MaterialType::Conductor: {
            const float alpha = conductor_alpha(m);
            if (alpha < kDeltaAlpha) return 0.0f;
            return ggx_reflection_pdf(p.frame.to_local(wo), p.frame.to_local(wi), alpha);
        }
        case MaterialType::Pbr: return pdf_pbr(m, p, wo, wi);
        case MaterialType::Mirror:
        case MaterialType::Dielectric:
        case MaterialType::Interface: return 0.0f;
    }
    return 0.0f;
}

bool sample_bsdf(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2, BsdfSample& out) {
    switch (m.type) {
        case MaterialType::Diffuse:
        case MaterialType::Phong: return sample_phong(m, p, wo, u_lobe, u1, u2, out);
        case MaterialType::Mirror:
            if (dot(wo, p.n_s) <= 0.0f) return false;
            return sample_specular_reflection(p, wo, m.kr, 1.0f, out);
        case MaterialType::Dielectric: return sample_dielectric(m, p, wo, u_lobe, out);
        case MaterialType::Pbr: return sample_pbr(m, p, wo, u_lobe, u1, u2, out);
        case MaterialType::Interface: return false;  // the integrators cross it before any BSDF
        case MaterialType::Conductor: {
            const Vec3 wo_l = p.frame.to_local(wo);
            if (wo_l.z <= 0.0f) return false;
            const float alpha = conductor_alpha(m);
            if (alpha < kDeltaAlpha) return sample_specular_reflection(p, wo, fresnel_schlick(m.ks, wo_l.z), 1.0f, out);
            const Vec3 h = sample_ggx_vndf(wo_l, alpha, u1, u2);
            const Vec3 wi_l = reflect(wo_l, h);
            if (wi_l.z <= 0.0f) return false;
            const Vec3 wi = p.frame.to_world(wi_l);
            if (dot(p.n_g, wi) <= 0.0f) return false;
            // The pdf of the world direction, exactly as pdf_bsdf computes it (the
            // peak of a sharp lobe is sensitive to the frame's rounding).
            const float pdf = ggx_reflection_pdf(wo_l, p.frame.to_local(wi), alpha);
            if (!(pdf > 0.0f)) return false;
            // f·cos θ_i / pdf = F·G1(ωi): D and G1(ωo)/cos θ_o cancel.
            out = BsdfSample{wi, fresnel_schlick(m.ks, dot(wo_l, h)) * ggx_g1(wi_l, alpha), pdf, false, false};
            return max_component(out.weight) > 0.0f;
        }
    }
    return false;
}

}  // namespace sombra
