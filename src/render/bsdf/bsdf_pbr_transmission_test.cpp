// Tests of the pbr material's KHR_materials_transmission and
// KHR_materials_volume lobes (render/bsdf/bsdf_pbr.cpp): the rough thin wall's
// BTDF against an independent double-precision transcription of the
// extension (render/bsdf/pbr_test_util.h), reciprocity, weight = f·|cos|/pdf,
// χ² of sampling against the pdf over the whole sphere, and the delta
// transmissions (thin wall and smooth refraction) against their closed
// forms. The rough volume's refraction has bsdf_pbr_refraction_test.cpp.
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
using bsdf_testing::random_sphere;
using bsdf_testing::rnd;
using bsdf_testing::to_dir;

constexpr double kPi = 3.14159265358979323846;
// Every χ² test in this file, for the Šidák correction of the suite's α = 0.01.
constexpr int kChi2Tests = 3 * 3 * 3 + 2;

Material glass(Vec3 base, float metallic, float roughness, float transmission, float thickness = 0.0f,
               float ior = 1.5f) {
    Material m;
    m.type = MaterialType::Pbr;
    m.base_color = base;
    m.metallic = metallic;
    m.roughness = roughness;
    m.transmission = transmission;
    m.thickness = thickness;
    m.ior = ior;
    return m;
}

const BsdfPoint kFlatInside = make_bsdf_point({0, 0, 1}, {0, 0, 1}, false);
// The same surface seen from below.
const BsdfPoint kBelow = make_bsdf_point({0, 0, -1}, {0, 0, -1}, false);

TEST(PbrTransmission, ThinWallMatchesTheExtension) {
    // Above: the core BRDF with its diffuse part scaled by 1 − t; below: the
    // extension's BTDF. 1e-3 relative as Pbr.EvalMatchesAppendixB (float rounding of h).
    std::uint64_t key = 20;
    for (const float r : {0.2f, 0.5f, 1.0f})
        for (const float metallic : {0.0f, 0.6f})
            for (const float t : {0.3f, 1.0f}) {
                const Material m = glass({0.9f, 0.5f, 0.2f}, metallic, r, t);
                ++key;
                int below = 0;
                for (std::uint32_t i = 0; i < 3000; ++i) {
                    const Vec3 wo = polar(89.0 * rnd(i, key), 6.0 * rnd(i, key + 1)), wi = random_sphere(i, key + 2);
                    const Vec3 f = eval_bsdf(m, kFlat, wo, wi);
                    for (int c = 0; c < 3; ++c) {
                        const ref::Params p = params(m, c);
                        const double expected = wi.z < 0 ? ref::thin_transmission(p, t, to_dir(wo), to_dir(wi))
                                                         : ref::brdf(p, to_dir(wo), to_dir(wi)) -
                                                               t * ref::diffuse_part(p, to_dir(wo), to_dir(wi));
                        ASSERT_NEAR(f[c], expected, 1e-3 * expected + 1e-6)
                            << "r " << r << " m " << metallic << " t " << t << " wo.z " << wo.z << " wi.z " << wi.z;
                    }
                    below += wi.z < 0 && max_component(f) > 0 ? 1 : 0;
                }
                EXPECT_GT(below, 1000);
            }
}

TEST(PbrTransmission, ThinWallIsReciprocal) {
    // f(ωo, ωi) seen from above equals f(ωi, ωo) seen from below.
    std::uint64_t key = 40;
    for (const float r : {0.2f, 0.6f}) {
        const Material m = glass({0.7f, 0.6f, 0.3f}, 0.2f, r, 0.8f);
        ++key;
        for (std::uint32_t i = 0; i < 2000; ++i) {
            const Vec3 wo = random_sphere(i, key), wi = random_sphere(i, key + 100);
            if (wo.z <= 0 || wi.z >= 0) continue;
            const Vec3 a = eval_bsdf(m, kFlat, wo, wi), b = eval_bsdf(m, kBelow, wi, wo);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-4f * a[c] + 1e-7f);
        }
    }
}

TEST(PbrTransmission, WeightIsFCosOverPdfAndDeltaLobesAreTheirClosedForms) {
    std::uint64_t key = 60;
    for (const float r : {0.0f, 0.4f})
        for (const float thickness : {0.0f, 1.0f})
            for (const bool outside : {true, false})
                for (const double theta : {10.0, 50.0, 80.0}) {
                    const Material m = glass({0.9f, 0.7f, 0.4f}, 0.1f, r, 0.8f, thickness);
                    const BsdfPoint& p = outside ? kFlat : kFlatInside;
                    const Vec3 wo = polar(theta, 0.5);
                    ++key;
                    int delta_through = 0, rough_through = 0;
                    for (std::uint32_t i = 0; i < 4000; ++i) {
                        BsdfSample s;
                        if (!sample_bsdf(m, p, wo, rnd(3 * i, key), rnd(3 * i + 1, key), rnd(3 * i + 2, key), s))
                            continue;
                        if (!s.transmission) continue;
                        ASSERT_LT(s.wi.z, 0.0f);
                        if (!s.delta) {
                            ++rough_through;
                            EXPECT_EQ(s.pdf, pdf_bsdf(m, p, wo, s.wi));
                            const Vec3 e = eval_bsdf(m, p, wo, s.wi) * (std::fabs(s.wi.z) / s.pdf);
                            for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], e[c], 1e-5f * std::max(1e-3f, e[c]));
                            continue;
                        }
                        ++delta_through;
                        // Thin: straight through; volume: Snell with η = η_i/η_t, radiance scaled by η².
                        const double eta = thickness > 0 ? (outside ? 1 / 1.5 : 1.5) : 1.0;
                        const double cos_o = wo.z, sin2_t = eta * eta * (1 - cos_o * cos_o);
                        ASSERT_LT(sin2_t, 1.0);
                        const double cos_t = std::sqrt(1 - sin2_t);
                        EXPECT_NEAR(s.wi.z, -cos_t, 1e-5);
                        EXPECT_NEAR(s.wi.x, -eta * wo.x, 1e-5);
                        // Schlick at the angle on the outer side: cos θ_o from outside, cos θ_t from inside.
                        const double cos_f = thickness > 0 && !outside ? cos_t : cos_o;
                        const double f0 = 0.04, fresnel = f0 + (1 - f0) * std::pow(1 - cos_f, 5);
                        for (int c = 0; c < 3; ++c) {
                            const double expected = (1 - 0.1) * 0.8 * (1 - fresnel) * m.base_color[c] * eta * eta;
                            EXPECT_NEAR(s.weight[c] * s.pdf, expected, 1e-5 * expected);
                        }
                    }
                    const double sin_o = std::sin(theta * kPi / 180);
                    // Total internal reflection at n; tilted facets of a rough volume let some light out.
                    const bool tir = thickness > 0 && !outside && 2.25 * sin_o * sin_o >= 1;
                    if (r == 0 && tir) {
                        EXPECT_EQ(delta_through + rough_through, 0);
                    } else if (r == 0) {
                        EXPECT_GT(delta_through, 400);
                        EXPECT_EQ(rough_through, 0);
                    } else {
                        EXPECT_EQ(delta_through, 0);
                        if (!tir) {
                            EXPECT_GT(rough_through, 400);
                        }
                    }
                }
}

TEST(PbrTransmission, TotalInternalReflectionInsideAVolume) {
    // From inside glass of ior 1.5 beyond the critical angle (41.8°) nothing
    // is transmitted, and the mirror takes everything: weight·pdf = 1.
    const Material m = glass(Vec3{1.0f}, 0.0f, 0.0f, 1.0f, 1.0f);
    const Vec3 wo = polar(50, 0.2);
    for (std::uint32_t i = 0; i < 200; ++i) {
        BsdfSample s;
        ASSERT_TRUE(sample_bsdf(m, kFlatInside, wo, rnd(i, 7), 0.5f, 0.5f, s));
        EXPECT_FALSE(s.transmission);
        EXPECT_NEAR(s.weight.x * s.pdf, 1.0f, 1e-6f);
    }
    // Metals transmit nothing.
    const Material metal = glass(Vec3{1.0f}, 1.0f, 0.0f, 1.0f);
    for (std::uint32_t i = 0; i < 200; ++i) {
        BsdfSample s;
        if (sample_bsdf(metal, kFlat, polar(30, 0.2), rnd(i, 8), 0.5f, 0.5f, s)) {
            EXPECT_FALSE(s.transmission);
        }
    }
}

// χ² of sample_bsdf against pdf_bsdf over the whole sphere (binned around
// n); delta samples count as failures, expected in proportion 1 − ∫pdf.
void expect_chi2(const Material& m, const BsdfPoint& p, Vec3 wo, std::uint64_t seed) {
    const auto sample = [&](std::uint32_t i) -> std::optional<Vec3> {
        BsdfSample s;
        if (!sample_bsdf(m, p, wo, rnd(3 * i, seed), rnd(3 * i + 1, seed), rnd(3 * i + 2, seed), s) || s.delta)
            return std::nullopt;
        return s.wi;
    };
    const auto pdf = [&](Vec3 wi) { return pdf_bsdf(m, p, wo, wi); };
    chi2::Options o;
    o.test_count = kChi2Tests;
    o.cos_bins = 20;
    const chi2::Result r = chi2::run(p.frame, sample, pdf, o);
    EXPECT_TRUE(r.passed) << "r " << m.roughness << " m " << m.metallic << " t " << m.transmission << ": " << r.message;
    if (std::getenv("SOMBRA_CHI2_VERBOSE")) std::printf("%s\n", r.message.c_str());
    const double f = r.success_fraction;
    EXPECT_NEAR(r.pdf_integral, f, 5 * std::sqrt(f * (1 - f) / o.samples) + 2e-3) << r.message;
}

TEST(PbrTransmission, Chi2SamplingMatchesThePdf) {
    std::uint64_t seed = 700;
    for (const float r : {0.1f, 0.4f, 1.0f})
        for (const float t : {0.3f, 0.7f, 1.0f})
            for (const double theta : {0.0, 45.0, 80.0})
                expect_chi2(glass({0.9f, 0.6f, 0.3f}, 0.2f, r, t), kFlat, polar(theta, -0.7), ++seed);
    // A smooth thin wall (delta mirror and transmission, diffuse rest) and a
    // rough volume (rough refraction and reflection, diffuse rest; more in
    // bsdf_pbr_refraction_test.cpp).
    expect_chi2(glass({0.8f, 0.8f, 0.8f}, 0.0f, 0.0f, 0.5f), kFlat, polar(30, 0.1), 801);
    expect_chi2(glass({0.8f, 0.8f, 0.8f}, 0.0f, 0.5f, 0.5f, 1.0f), kFlatInside, polar(20, 0.1), 802);
}

TEST(PbrTransmission, SmoothWhiteThinWallConservesEnergy) {
    // Base colour 1, transmission 1: what the layer does not reflect goes
    // through, so the weights average to 1 (F + (1 − F)).
    const Material m = glass(Vec3{1.0f}, 0.0f, 0.0f, 1.0f);
    EXPECT_TRUE(is_delta_bsdf(m));
    for (const double theta : {0.0, 40.0, 85.0}) {
        double sum = 0;
        const std::uint32_t n = 20000;
        for (std::uint32_t i = 0; i < n; ++i) {
            BsdfSample s;
            if (sample_bsdf(m, kFlat, polar(theta, 0.3), rnd(i, 9), 0.5f, 0.5f, s)) sum += s.weight.x;
        }
        const double fresnel = 0.04 + 0.96 * std::pow(1 - std::cos(theta * kPi / 180), 5);
        // Each sample's weight is F/P_s or (1 − F)/(1 − P_s): the mean's error is
        // bounded by the binomial spread of the choice; 5σ of it.
        const double ps = std::clamp(fresnel / (fresnel + (1 - fresnel)), 0.25, 0.9);
        const double spread = std::fabs(fresnel / ps - (1 - fresnel) / (1 - ps)) * std::sqrt(ps * (1 - ps) / n);
        EXPECT_NEAR(sum / n, 1.0, 5 * spread + 1e-6) << theta;
    }
}

}  // namespace
}  // namespace sombra
