// Tests of KHR_materials_sheen over the pbr material
// (render/bsdf/bsdf_pbr_sheen.cpp): values against an independent
// double-precision transcription of the extension's sheen lobe and
// albedo-scaling layer (render/bsdf/pbr_test_util.h; E from the table that
// sheen_test.cpp checks against brute force), reciprocity, weight =
// f·|cos|/pdf, χ² of sampling against the pdf, the white furnace's bound,
// the coat over the sheen, and no change without a sheen.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <utility>
#include <vector>

#include "render/bsdf/bsdf.h"
#include "render/bsdf/bsdf_test_util.h"
#include "render/bsdf/pbr_test_util.h"
#include "render/bsdf/sheen.h"
#include "render/chi2_test_util.h"
#include "render/sampler.h"

namespace sombra {
namespace {

namespace ref = pbr_reference;
using bsdf_testing::kFlat;
using bsdf_testing::params;
using bsdf_testing::polar;
using bsdf_testing::random_upper;
using bsdf_testing::rnd;
using bsdf_testing::to_dir;

// Every χ² test in this file, for the Šidák correction of the suite's α = 0.01.
constexpr int kChi2Tests = 3 * 2 * 3 + 2;

Material sheened(Vec3 base, float metallic, float roughness, Vec3 sheen, float sheen_roughness) {
    Material m;
    m.type = MaterialType::Pbr;
    m.base_color = base;
    m.metallic = metallic;
    m.roughness = roughness;
    m.sheen_color = sheen;
    m.sheen_roughness = sheen_roughness;
    return m;
}

std::vector<Material> materials() {
    std::vector<Material> out;
    for (const float sheen_r : {0.2f, 0.5f, 1.0f})
        for (const float r : {0.0f, 0.5f})
            for (const float metallic : {0.0f, 1.0f})
                out.push_back(sheened({0.9f, 0.5f, 0.1f}, metallic, r, {1.0f, 1.0f, 1.0f}, sheen_r));
    out.push_back(sheened({0.2f, 0.3f, 0.8f}, 0.3f, 0.3f, {0.9f, 0.4f, 0.1f}, 0.4f));
    return out;
}

// The extension's sheen_material for channel c: sheen colour times the lobe,
// plus the base scaled by min(1 − max3(sheen)·E(N·V), 1 − max3(sheen)·E(N·L)),
// never below 0.
double expected_f(const Material& m, int c, Vec3 wo, Vec3 wi) {
    const ref::Params p = params(m, c);
    const double base =
        m.roughness > 0 ? ref::brdf(p, to_dir(wo), to_dir(wi)) : ref::diffuse_part(p, to_dir(wo), to_dir(wi));
    const double s = max_component(m.sheen_color);
    const double scale = std::max(0.0, std::min(1.0 - s * sheen_albedo(wo.z, m.sheen_roughness),
                                                1.0 - s * sheen_albedo(wi.z, m.sheen_roughness)));
    return m.sheen_color[c] * ref::sheen_lobe(to_dir(wo), to_dir(wi), m.sheen_roughness) + base * scale;
}

TEST(PbrSheen, EvalMatchesTheExtension) {
    std::uint64_t key = 130;
    for (const Material& m : materials()) {
        ++key;
        for (std::uint32_t i = 0; i < 3000; ++i) {
            const Vec3 wo = random_upper(i, key), wi = random_upper(i, key + 1000);
            const Vec3 f = eval_bsdf(m, kFlat, wo, wi);
            const BsdfTerms t = eval_bsdf_terms(m, kFlat, wo, wi);
            for (int c = 0; c < 3; ++c) {
                const double expected = expected_f(m, c, wo, wi);
                ASSERT_NEAR(f[c], expected, 1e-3 * expected + 1e-6)
                    << "r " << m.roughness << " m " << m.metallic << " sheen r " << m.sheen_roughness << " wo.z "
                    << wo.z << " wi.z " << wi.z;
                // The terms add up to f, and the sheen term is the lobe's.
                const float sum = t.diffuse[c] + t.lobe[c] + t.sheen[c];
                ASSERT_NEAR(sum, f[c], 1e-6f * f[c]);
                const double lobe = m.sheen_color[c] * ref::sheen_lobe(to_dir(wo), to_dir(wi), m.sheen_roughness);
                ASSERT_NEAR(t.sheen[c], lobe, 1e-3 * lobe + 1e-7);
            }
        }
    }
}

TEST(PbrSheen, NoSheenIsTheBaseBitForBit) {
    Material m = sheened({0.7f, 0.4f, 0.2f}, 0.3f, 0.4f, Vec3{0.0f}, 0.5f);
    Material base = m;
    base.sheen_roughness = 0.0f;
    for (std::uint32_t i = 0; i < 500; ++i) {
        const Vec3 wo = random_upper(i, 3), wi = random_upper(i, 4);
        EXPECT_EQ(eval_bsdf(m, kFlat, wo, wi), eval_bsdf(base, kFlat, wo, wi));
        EXPECT_EQ(pdf_bsdf(m, kFlat, wo, wi), pdf_bsdf(base, kFlat, wo, wi));
        BsdfSample a, b;
        const bool ok = sample_bsdf(m, kFlat, wo, rnd(3 * i, 5), rnd(3 * i + 1, 5), rnd(3 * i + 2, 5), a);
        ASSERT_EQ(ok, sample_bsdf(base, kFlat, wo, rnd(3 * i, 5), rnd(3 * i + 1, 5), rnd(3 * i + 2, 5), b));
        if (ok) {
            EXPECT_EQ(a.wi, b.wi);
            EXPECT_EQ(a.weight, b.weight);
            EXPECT_EQ(a.pdf, b.pdf);
        }
    }
}

// The lobe is symmetric, the base is, and the scaling takes the smaller
// of the two directions' values: f(ωo, ωi) = f(ωi, ωo).
TEST(PbrSheen, IsReciprocal) {
    std::uint64_t key = 170;
    for (const Material& m : materials()) {
        ++key;
        for (std::uint32_t i = 0; i < 2000; ++i) {
            const Vec3 wo = random_upper(i, key), wi = random_upper(i, key + 1000);
            const Vec3 a = eval_bsdf(m, kFlat, wo, wi), b = eval_bsdf(m, kFlat, wi, wo);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-4f * a[c] + 1e-7f) << wo.z << " " << wi.z;
        }
    }
}

TEST(PbrSheen, WeightIsFCosOverPdfAndTheSmoothBasesMirrorIsScaled) {
    std::uint64_t key = 250;
    for (const Material& m : materials())
        for (const double theta : {0.0, 45.0, 80.0}) {
            const Vec3 wo = polar(theta, 0.4);
            ++key;
            int rough = 0, delta = 0;
            for (std::uint32_t i = 0; i < 3000; ++i) {
                BsdfSample s;
                if (!sample_bsdf(m, kFlat, wo, rnd(3 * i, key), rnd(3 * i + 1, key), rnd(3 * i + 2, key), s)) continue;
                if (!s.delta) {
                    ++rough;
                    EXPECT_EQ(s.pdf, pdf_bsdf(m, kFlat, wo, s.wi));
                    const Vec3 e = eval_bsdf(m, kFlat, wo, s.wi) * (std::fabs(s.wi.z) / s.pdf);
                    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], e[c], 1e-5f * std::max(1e-3f, e[c]));
                    continue;
                }
                // The base's mirror (a metal's: Schlick from the base colour),
                // under 1 − max3(sheen)·E(cos θ_o).
                ++delta;
                if (m.metallic == 1.0f) {
                    const float scale = 1.0f - max_component(m.sheen_color) * sheen_albedo(wo.z, m.sheen_roughness);
                    const double w = std::pow(1 - wo.z, 5);
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(s.weight[c] * s.pdf, scale * (m.base_color[c] + (1 - m.base_color[c]) * w), 1e-5);
                }
            }
            EXPECT_GT(rough, 200) << "r " << m.roughness << " m " << m.metallic << " at " << theta;
            EXPECT_EQ(delta > 0, m.roughness == 0.0f);
            // A smooth metal under a sheen is no longer a delta material: lights are sampled for it.
            EXPECT_FALSE(is_delta_bsdf(m));
        }
}

void expect_chi2(const Material& m, Vec3 wo, std::uint64_t seed) {
    const auto sample = [&](std::uint32_t i) -> std::optional<Vec3> {
        BsdfSample s;
        if (!sample_bsdf(m, kFlat, wo, rnd(3 * i, seed), rnd(3 * i + 1, seed), rnd(3 * i + 2, seed), s) || s.delta)
            return std::nullopt;
        return s.wi;
    };
    // Where f is 0 (0 in float: the base's share scaled to 0 where E(cos θ_i)
    // exceeds 1, and the lobe underflowing for a smooth sheen) a sample has
    // zero weight and is not returned (render/bsdf/bsdf.h): the density of the
    // returned samples is pdf_bsdf there only where f > 0.
    const auto pdf = [&](Vec3 wi) {
        return max_component(eval_bsdf(m, kFlat, wo, wi)) > 0.0f ? pdf_bsdf(m, kFlat, wo, wi) : 0.0f;
    };
    chi2::Options o;
    o.test_count = kChi2Tests;
    const chi2::Result r = chi2::run(Frame::from_normal({0, 0, 1}), sample, pdf, o);
    EXPECT_TRUE(r.passed) << "r " << m.roughness << " m " << m.metallic << " sheen r " << m.sheen_roughness << ": "
                          << r.message;
    if (std::getenv("SOMBRA_CHI2_VERBOSE")) std::printf("%s\n", r.message.c_str());
    const double f = r.success_fraction;
    EXPECT_NEAR(r.pdf_integral, f, 5 * std::sqrt(f * (1 - f) / o.samples) + 2e-3) << r.message;
}

TEST(PbrSheen, Chi2SamplingMatchesThePdf) {
    std::uint64_t seed = 1900;
    for (const float sheen_r : {0.1f, 0.4f, 1.0f})
        for (const float r : {0.0f, 0.5f})
            for (const double theta : {10.0, 50.0, 80.0})
                expect_chi2(sheened({0.8f, 0.6f, 0.3f}, 0.2f, r, {1.0f, 0.8f, 0.5f}, sheen_r), polar(theta, 0.9),
                            ++seed);
    expect_chi2(sheened({0.8f, 0.6f, 0.3f}, 1.0f, 0.0f, Vec3{1.0f}, 0.5f), polar(40, 0.9), 1951);
    Material coated = sheened({0.5f, 0.5f, 0.5f}, 0.0f, 0.4f, Vec3{0.7f}, 0.6f);
    coated.clearcoat = 1.0f;
    coated.clearcoat_roughness = 0.2f;
    expect_chi2(coated, polar(60, 0.9), 1952);
}

// The mean weight of 200 000 samples from ωo (the directional albedo ∫ f·cos),
// and its standard error.
std::pair<double, double> albedo(const Material& m, Vec3 wo, std::uint64_t seed) {
    constexpr std::uint32_t n = 200000;
    double sum = 0, sum2 = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        BsdfSample s;
        if (!sample_bsdf(m, kFlat, wo, rnd(3 * i, seed), rnd(3 * i + 1, seed), rnd(3 * i + 2, seed), s)) continue;
        sum += s.weight.x;
        sum2 += double(s.weight.x) * s.weight.x;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

// The white furnace: under a white sheen a white base reflects at most
// c·E + (1 − c·E)·A_base (the layer returns E and leaves the base at most
// 1 − E of its share), so at most all the light wherever the base's own
// albedo A_base is at most 1. (glTF's core model is not energy conserving:
// at 75° its smooth white dielectric reflects 1.2; the layer does not add
// to that.) E is the table's: the lobe's true albedo may exceed it by the
// lookup's 0.0045 (sheen_test.cpp); 4 standard errors of each estimate.
TEST(PbrSheen, WhiteFurnaceGainsNoEnergyFromTheSheen) {
    std::uint64_t seed = 2100;
    for (const float r : {0.1f, 0.5f, 1.0f})
        for (const double theta : {0.0, 45.0, 75.0}) {
            const Vec3 wo = polar(theta, 0.3);
            const auto [base, base_error] = albedo(sheened(Vec3{1.0f}, 0.0f, r, Vec3{0.0f}, 0.0f), wo, ++seed);
            for (const float sheen_r : {0.3f, 0.6f, 1.0f}) {
                const auto [total, error] = albedo(sheened(Vec3{1.0f}, 0.0f, r, Vec3{1.0f}, sheen_r), wo, ++seed);
                const double e = sheen_albedo(wo.z, sheen_r);
                ASSERT_LE(e, 1.0);
                const double slack = 4 * (error + base_error) + 0.0045;
                EXPECT_LE(total, e + (1 - e) * base + slack) << "sheen r " << sheen_r << " r " << r << " at " << theta
                                                             << ": " << total << " ± " << error << ", base " << base;
                if (base <= 1.0) {
                    EXPECT_LE(total, 1.0 + slack) << "sheen r " << sheen_r << " r " << r << " at " << theta;
                }
            }
        }
}

// The coat lies over the sheen: the sheen term is scaled by 1 − k·F_c as
// the rest of the base is.
TEST(PbrSheen, TheCoatCoversTheSheen) {
    Material m = sheened({0.5f, 0.5f, 0.5f}, 0.0f, 0.4f, {0.9f, 0.6f, 0.3f}, 0.5f);
    Material coated = m;
    coated.clearcoat = 1.0f;
    coated.clearcoat_roughness = 0.3f;
    for (std::uint32_t i = 0; i < 500; ++i) {
        const Vec3 wo = random_upper(i, 11), wi = random_upper(i, 12);
        const double blend = 0.04 + 0.96 * std::pow(1 - wo.z, 5);
        const BsdfTerms a = eval_bsdf_terms(m, kFlat, wo, wi), b = eval_bsdf_terms(coated, kFlat, wo, wi);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.sheen[c], (1 - blend) * a.sheen[c], 1e-5 * a.sheen[c] + 1e-9);
    }
}

}  // namespace
}  // namespace sombra
