// Tests of KHR_materials_clearcoat's own coat normal (BsdfPoint::n_c,
// render/bsdf/bsdf_pbr_layers.cpp): with the base's n_s and the coat's n_c
// tilted apart, f·|n_s·ωi| against an independent double-precision
// transcription of the extension's fresnel_coat with each layer in its own
// normal's frame (render/bsdf/pbr_test_util.h), weight = f·|n_s·ωi|/pdf, the
// smooth coat's mirror about n_c, χ² of sampling against the pdf, and the
// sidedness rule (nothing across n_g).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "render/bsdf/bsdf.h"
#include "render/bsdf/bsdf_test_util.h"
#include "render/bsdf/pbr_test_util.h"
#include "render/chi2_test_util.h"

namespace sombra {
namespace {

namespace ref = pbr_reference;
using bsdf_testing::params;
using bsdf_testing::polar;
using bsdf_testing::random_upper;
using bsdf_testing::rnd;

// Every χ² test in this file, for the Šidák correction of the suite's α = 0.01.
constexpr int kChi2Tests = 3 * 2 * 2;

Material coated(float roughness, float clearcoat, float coat_roughness) {
    Material m;
    m.type = MaterialType::Pbr;
    m.base_color = {0.8f, 0.5f, 0.2f};
    m.metallic = 0.2f;
    m.roughness = roughness;
    m.clearcoat = clearcoat;
    m.clearcoat_roughness = coat_roughness;
    return m;
}

// n_g = +z, the base's normal tilted towards +x, the coat's towards −y.
const Vec3 kBaseNormal = polar(25, 0.0), kCoatNormal = polar(20, -1.5);
const BsdfPoint kTilted = make_bsdf_point({0, 0, 1}, kBaseNormal, true, kCoatNormal);

// v in an orthonormal frame around unit n (double precision, built apart
// from Frame): any frame serves, the lobes being isotropic.
ref::Dir local(Vec3 n_f, Vec3 v_f) {
    const ref::Dir n{n_f.x, n_f.y, n_f.z}, v{v_f.x, v_f.y, v_f.z};
    const ref::Dir a = std::fabs(n.x) < 0.9 ? ref::Dir{1, 0, 0} : ref::Dir{0, 1, 0};
    // s = normalize(a − (a·n)n), t = n × s.
    const double an = ref::dot(a, n);
    ref::Dir s{a.x - an * n.x, a.y - an * n.y, a.z - an * n.z};
    const double len = std::sqrt(ref::dot(s, s));
    s = {s.x / len, s.y / len, s.z / len};
    const ref::Dir t{n.y * s.z - n.z * s.y, n.z * s.x - n.x * s.z, n.x * s.y - n.y * s.x};
    return {ref::dot(v, s), ref::dot(v, t), ref::dot(v, n)};
}

// The extension's f·cos for V, L above n_g with V above both normals:
// (1 − k·F_c(n_c·V))·base(n_s)·(n_s·L) + k·F_c(n_c·V)·specular_brdf(α_c; n_c)·(n_c·L).
double reference_f_cos(const Material& m, int c, Vec3 wo, Vec3 wi) {
    const ref::Dir vs = local(kBaseNormal, wo), ls = local(kBaseNormal, wi);
    const ref::Dir vc = local(kCoatNormal, wo), lc = local(kCoatNormal, wi);
    const double base = ref::brdf(params(m, c), vs, ls) * std::max(0.0, ls.z);
    const double blend = m.clearcoat * (0.04 + 0.96 * std::pow(1 - vc.z, 5));
    const double layer = ref::coated(0.0, m.clearcoat, m.clearcoat_roughness, vc, lc) * std::max(0.0, lc.z);
    return (1 - blend) * base + layer;
}

TEST(PbrCoatNormal, EvalMatchesTheExtensionInEachLayersFrame) {
    std::uint64_t key = 70;
    int compared = 0, coat_only = 0;
    for (const float coat_r : {0.2f, 0.5f})
        for (const float clearcoat : {1.0f, 0.5f}) {
            const Material m = coated(0.6f, clearcoat, coat_r);
            ++key;
            for (std::uint32_t i = 0; i < 4000; ++i) {
                const Vec3 wo = random_upper(i, key), wi = random_upper(i, key + 1000);
                if (dot(wo, kBaseNormal) <= 0.0f || dot(wo, kCoatNormal) <= 0.0f) continue;
                const Vec3 f_cos = eval_bsdf(m, kTilted, wo, wi) * std::fabs(dot(kBaseNormal, wi));
                if (dot(wi, kBaseNormal) <= 0.0f && dot(wi, kCoatNormal) > 0.0f) ++coat_only;
                ++compared;
                for (int c = 0; c < 3; ++c) {
                    const double expected = reference_f_cos(m, c, wo, wi);
                    ASSERT_NEAR(f_cos[c], expected, 2e-3 * expected + 1e-6)
                        << "coat r " << coat_r << " k " << clearcoat << " wo " << wo.x << " " << wo.y << " " << wo.z
                        << " wi " << wi.x << " " << wi.y << " " << wi.z;
                }
            }
        }
    EXPECT_GT(compared, 8000);
    EXPECT_GT(coat_only, 100);  // directions only the coat sees
}

TEST(PbrCoatNormal, TheTermsNameTheCoatWithItsOwnNormal) {
    const Material m = coated(0.6f, 1.0f, 0.3f);
    for (std::uint32_t i = 0; i < 500; ++i) {
        const Vec3 wo = random_upper(i, 5), wi = random_upper(i, 6);
        if (dot(wo, kBaseNormal) <= 0.0f || dot(wo, kCoatNormal) <= 0.0f || dot(wi, kBaseNormal) <= 0.0f) continue;
        const BsdfTerms t = eval_bsdf_terms(m, kTilted, wo, wi);
        const ref::Dir vc = local(kCoatNormal, wo), lc = local(kCoatNormal, wi);
        const double expected = ref::coated(0.0, 1.0, 0.3, vc, lc) * std::max(0.0, lc.z) / dot(kBaseNormal, wi);
        EXPECT_NEAR(t.coat.x, expected, 2e-3 * expected + 1e-6);
        const Vec3 sum = t.diffuse + t.lobe + t.transmission + t.coat + t.sheen;
        const Vec3 f = eval_bsdf(m, kTilted, wo, wi);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], f[c], 1e-5f * std::max(1.0f, f[c]));
    }
}

TEST(PbrCoatNormal, NothingAcrossTheGeometricNormal) {
    const Material m = coated(0.6f, 1.0f, 0.4f);
    const Vec3 wo = polar(30, 0.3);
    // Below n_g, yet above n_c (tilted towards −y): still 0.
    const Vec3 wi = normalize(Vec3{0.0f, -1.0f, -0.1f});
    ASSERT_GT(dot(wi, kCoatNormal), 0.0f);
    EXPECT_EQ(eval_bsdf(m, kTilted, wo, wi), Vec3{0.0f});
    EXPECT_EQ(pdf_bsdf(m, kTilted, wo, wi), 0.0f);
    for (std::uint32_t i = 0; i < 2000; ++i) {
        BsdfSample s;
        if (sample_bsdf(m, kTilted, wo, rnd(3 * i, 8), rnd(3 * i + 1, 8), rnd(3 * i + 2, 8), s)) {
            EXPECT_GT(s.wi.z, 0.0f);
        }
    }
}

TEST(PbrCoatNormal, WeightIsFCosOverPdfAndTheSmoothCoatMirrorsAboutItsNormal) {
    std::uint64_t key = 80;
    for (const float coat_r : {0.0f, 0.3f})
        for (const double theta : {10.0, 45.0, 70.0}) {
            const Material m = coated(0.5f, 1.0f, coat_r);
            const Vec3 wo = polar(theta, 0.7);
            ++key;
            int rough = 0, coat_mirror = 0;
            for (std::uint32_t i = 0; i < 3000; ++i) {
                BsdfSample s;
                if (!sample_bsdf(m, kTilted, wo, rnd(3 * i, key), rnd(3 * i + 1, key), rnd(3 * i + 2, key), s))
                    continue;
                if (s.delta) {
                    // Only the coat is a delta here: the mirror about n_c, weight·pdf = k·F_c(n_c·ωo).
                    const float cos_c = dot(wo, kCoatNormal);
                    const Vec3 mirror = 2.0f * cos_c * kCoatNormal - wo;
                    EXPECT_NEAR(length(s.wi - mirror), 0.0f, 1e-5f);
                    const double fc = 0.04 + 0.96 * std::pow(1.0 - cos_c, 5);
                    EXPECT_NEAR(s.weight.x * s.pdf, fc, 1e-5);
                    ++coat_mirror;
                    continue;
                }
                ++rough;
                EXPECT_EQ(s.pdf, pdf_bsdf(m, kTilted, wo, s.wi));
                const Vec3 e = eval_bsdf(m, kTilted, wo, s.wi) * (std::fabs(dot(kBaseNormal, s.wi)) / s.pdf);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], e[c], 1e-5f * std::max(1e-3f, e[c]));
            }
            EXPECT_GT(rough, 300) << theta;
            // At 70° the mirror about n_c falls below n_g: never produced.
            const Vec3 mirror = 2.0f * dot(wo, kCoatNormal) * kCoatNormal - wo;
            if (coat_r == 0.0f && mirror.z > 0.0f) {
                EXPECT_GT(coat_mirror, 200) << theta;
            }
            if (mirror.z <= 0.0f) {
                EXPECT_EQ(coat_mirror, 0) << theta;
            }
        }
}

void expect_chi2(const Material& m, Vec3 wo, std::uint64_t seed) {
    const auto sample = [&](std::uint32_t i) -> std::optional<Vec3> {
        BsdfSample s;
        if (!sample_bsdf(m, kTilted, wo, rnd(3 * i, seed), rnd(3 * i + 1, seed), rnd(3 * i + 2, seed), s) || s.delta)
            return std::nullopt;
        return s.wi;
    };
    const auto pdf = [&](Vec3 wi) { return pdf_bsdf(m, kTilted, wo, wi); };
    chi2::Options o;
    o.test_count = kChi2Tests;
    // Binned around the coat's mirror direction, where its lobe peaks.
    const Vec3 mirror = normalize(2.0f * dot(wo, kCoatNormal) * kCoatNormal - wo);
    const chi2::Result r = chi2::run(Frame::from_normal(mirror), sample, pdf, o);
    EXPECT_TRUE(r.passed) << "r " << m.roughness << " coat r " << m.clearcoat_roughness << ": " << r.message;
    if (std::getenv("SOMBRA_CHI2_VERBOSE")) std::printf("%s\n", r.message.c_str());
    const double f = r.success_fraction;
    EXPECT_NEAR(r.pdf_integral, f, 5 * std::sqrt(f * (1 - f) / o.samples) + 2e-3) << r.message;
}

TEST(PbrCoatNormal, Chi2SamplingMatchesThePdf) {
    std::uint64_t seed = 1900;
    for (const float coat_r : {0.05f, 0.3f, 0.8f})
        for (const float r : {0.0f, 0.5f})
            for (const double theta : {20.0, 70.0}) expect_chi2(coated(r, 1.0f, coat_r), polar(theta, 2.0), ++seed);
}

}  // namespace
}  // namespace sombra
