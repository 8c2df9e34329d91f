// Tests of KHR_materials_clearcoat over the pbr material
// (render/bsdf/bsdf_pbr_layers.cpp): values against an independent
// double-precision transcription of the extension's fresnel_coat
// (render/bsdf/pbr_test_util.h), weight = f·|cos|/pdf, the smooth coat's delta
// weight, χ² of sampling against the pdf, and no change without a coat.
// (The coat's Fresnel is taken at n·ωo, as the extension says, so the
// coated BSDF is not reciprocal: there is no reciprocity test.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <vector>

#include "render/bsdf/bsdf.h"
#include "render/bsdf/bsdf_test_util.h"
#include "render/bsdf/pbr_test_util.h"
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

constexpr double kPi = 3.14159265358979323846;
// Every χ² test in this file, for the Šidák correction of the suite's α = 0.01.
constexpr int kChi2Tests = 3 * 2 * 3 + 2;

Material coated(Vec3 base, float metallic, float roughness, float clearcoat, float coat_roughness) {
    Material m;
    m.type = MaterialType::Pbr;
    m.base_color = base;
    m.metallic = metallic;
    m.roughness = roughness;
    m.clearcoat = clearcoat;
    m.clearcoat_roughness = coat_roughness;
    return m;
}

std::vector<Material> materials() {
    std::vector<Material> out;
    for (const float coat_r : {0.0f, 0.15f, 0.6f})
        for (const float r : {0.0f, 0.5f})
            for (const float metallic : {0.0f, 1.0f})
                out.push_back(coated({0.9f, 0.5f, 0.1f}, metallic, r, 1.0f, coat_r));
    out.push_back(coated({0.2f, 0.3f, 0.8f}, 0.3f, 0.3f, 0.4f, 0.3f));
    return out;
}

TEST(PbrClearcoat, EvalMatchesTheExtension) {
    std::uint64_t key = 30;
    for (const Material& m : materials()) {
        ++key;
        for (std::uint32_t i = 0; i < 3000; ++i) {
            const Vec3 wo = random_upper(i, key), wi = random_upper(i, key + 1000);
            const Vec3 f = eval_bsdf(m, kFlat, wo, wi);
            for (int c = 0; c < 3; ++c) {
                const ref::Params p = params(m, c);
                const double base = m.roughness > 0 ? ref::brdf(p, to_dir(wo), to_dir(wi))
                                                    : ref::diffuse_part(p, to_dir(wo), to_dir(wi));
                const double expected = ref::coated(base, m.clearcoat, m.clearcoat_roughness, to_dir(wo), to_dir(wi));
                ASSERT_NEAR(f[c], expected, 1e-3 * expected + 1e-7)
                    << "r " << m.roughness << " m " << m.metallic << " coat r " << m.clearcoat_roughness << " wo.z "
                    << wo.z << " wi.z " << wi.z;
            }
        }
    }
}

TEST(PbrClearcoat, NoCoatIsTheBaseBitForBit) {
    Material m = coated({0.7f, 0.4f, 0.2f}, 0.3f, 0.4f, 0.0f, 0.5f);
    Material base = m;
    base.clearcoat_roughness = 0.0f;
    for (std::uint32_t i = 0; i < 500; ++i) {
        const Vec3 wo = random_upper(i, 3), wi = random_upper(i, 4);
        EXPECT_EQ(eval_bsdf(m, kFlat, wo, wi), eval_bsdf(base, kFlat, wo, wi));
        EXPECT_EQ(pdf_bsdf(m, kFlat, wo, wi), pdf_bsdf(base, kFlat, wo, wi));
    }
}

TEST(PbrClearcoat, WeightIsFCosOverPdfAndTheSmoothCoatIsItsFresnel) {
    std::uint64_t key = 50;
    for (const Material& m : materials())
        for (const double theta : {0.0, 45.0, 80.0}) {
            const Vec3 wo = polar(theta, 0.4);
            ++key;
            int coat_mirror = 0, rough = 0, delta = 0;
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
                ++delta;
                // A delta: the coat's mirror (weight·pdf = k·F_c, grey) or the base's (times 1 − k·F_c).
                const double fc = m.clearcoat * (0.04 + 0.96 * std::pow(1 - std::cos(theta * kPi / 180), 5));
                if (m.clearcoat_roughness == 0 && std::fabs(s.weight.x * s.pdf - fc) < 1e-5 &&
                    std::fabs(s.weight.z * s.pdf - fc) < 1e-5)
                    ++coat_mirror;
            }
            EXPECT_GT(rough + delta, 2000)
                << "r " << m.roughness << " m " << m.metallic << " coat r " << m.clearcoat_roughness << " at " << theta;
            if (m.clearcoat_roughness == 0) {
                EXPECT_GT(coat_mirror, 200);
            }
        }
}

void expect_chi2(const Material& m, Vec3 wo, std::uint64_t seed) {
    const Vec3 mirror = normalize(2.0f * wo.z * Vec3{0, 0, 1} - wo);
    const auto sample = [&](std::uint32_t i) -> std::optional<Vec3> {
        BsdfSample s;
        if (!sample_bsdf(m, kFlat, wo, rnd(3 * i, seed), rnd(3 * i + 1, seed), rnd(3 * i + 2, seed), s) || s.delta)
            return std::nullopt;
        return s.wi;
    };
    const auto pdf = [&](Vec3 wi) { return pdf_bsdf(m, kFlat, wo, wi); };
    chi2::Options o;
    o.test_count = kChi2Tests;
    const chi2::Result r = chi2::run(Frame::from_normal(mirror), sample, pdf, o);
    EXPECT_TRUE(r.passed) << "r " << m.roughness << " m " << m.metallic << " coat r " << m.clearcoat_roughness << ": "
                          << r.message;
    if (std::getenv("SOMBRA_CHI2_VERBOSE")) std::printf("%s\n", r.message.c_str());
    const double f = r.success_fraction;
    EXPECT_NEAR(r.pdf_integral, f, 5 * std::sqrt(f * (1 - f) / o.samples) + 2e-3) << r.message;
}

TEST(PbrClearcoat, Chi2SamplingMatchesThePdf) {
    std::uint64_t seed = 900;
    for (const float coat_r : {0.05f, 0.3f, 0.8f})
        for (const float r : {0.0f, 0.5f})
            for (const double theta : {10.0, 50.0, 80.0})
                expect_chi2(coated({0.8f, 0.6f, 0.3f}, 0.2f, r, 1.0f, coat_r), polar(theta, 0.9), ++seed);
    expect_chi2(coated({0.8f, 0.6f, 0.3f}, 1.0f, 0.6f, 0.5f, 0.0f), polar(40, 0.9), 951);
    expect_chi2(coated(Vec3{0.0f}, 0.0f, 0.3f, 1.0f, 0.2f), polar(60, 0.9), 952);
}

}  // namespace
}  // namespace sombra
