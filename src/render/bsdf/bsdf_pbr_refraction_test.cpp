// Tests of the pbr material's rough refraction through a
// KHR_materials_volume interface (render/bsdf/bsdf_pbr.cpp, Walter et al. 2007):
// the BTDF against an independent double-precision transcription of
// Walter's formulas (render/bsdf/pbr_test_util.h), generalized reciprocity,
// weight = f·|cos|/pdf, χ² of sampling against the pdf over the whole
// sphere from both sides, and the limit α → 0, where the rough refraction
// must carry what the smooth (delta) one does.
#include <gtest/gtest.h>

#include <algorithm>
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
using bsdf_testing::kFlat;
using bsdf_testing::params;
using bsdf_testing::polar;
using bsdf_testing::random_sphere;
using bsdf_testing::rnd;
using bsdf_testing::to_dir;

// Every χ² test in this file, for the Šidák correction of the suite's α = 0.01.
constexpr int kChi2Tests = 3 * 3 * 2 + 2;

Material volume(Vec3 base, float metallic, float roughness, float transmission, float ior = 1.5f) {
    Material m;
    m.type = MaterialType::Pbr;
    m.base_color = base;
    m.metallic = metallic;
    m.roughness = roughness;
    m.transmission = transmission;
    m.thickness = 1.0f;
    m.ior = ior;
    return m;
}

// The surface seen from inside the volume, n = +z (wo above is inside).
const BsdfPoint kFlatInside = make_bsdf_point({0, 0, 1}, {0, 0, 1}, false);
// The same surface as kFlat seen from below, i.e. from inside the volume.
const BsdfPoint kBelowInside = make_bsdf_point({0, 0, -1}, {0, 0, -1}, false);

TEST(PbrRefraction, RoughVolumeTransmitsDiffusely) {
    EXPECT_TRUE(transmits_diffusely(volume(Vec3{1.0f}, 0.0f, 0.3f, 1.0f)));
    EXPECT_FALSE(transmits_diffusely(volume(Vec3{1.0f}, 0.0f, 0.0f, 1.0f)));        // smooth: the delta
    EXPECT_FALSE(transmits_diffusely(volume(Vec3{1.0f}, 0.0f, 0.3f, 1.0f, 1.0f)));  // ior 1 does not bend
    EXPECT_FALSE(transmits_diffusely(volume(Vec3{1.0f}, 1.0f, 0.3f, 1.0f)));        // metals transmit nothing
    EXPECT_FALSE(is_delta_bsdf(volume(Vec3{1.0f}, 0.0f, 0.3f, 1.0f)));
}

TEST(PbrRefraction, EvalMatchesWalter) {
    // 1e-3 relative, as the other pbr lobes' tests (float rounding of h).
    std::uint64_t key = 10;
    for (const float r : {0.2f, 0.5f, 1.0f})
        for (const float metallic : {0.0f, 0.4f})
            for (const float ior : {1.5f, 2.2f})
                for (const bool outside : {true, false}) {
                    Material m = volume({0.9f, 0.5f, 0.2f}, metallic, r, 0.8f, ior);
                    if (metallic > 0) {  // KHR_materials_specular's max over a coloured F0
                        m.specular = 0.8f;
                        m.specular_color = {1.2f, 0.6f, 0.9f};
                    }
                    const BsdfPoint& p = outside ? kFlat : kFlatInside;
                    ++key;
                    int through = 0;
                    for (std::uint32_t i = 0; i < 3000; ++i) {
                        const Vec3 wo = polar(89.0 * rnd(i, key), 6.0 * rnd(i, key + 1));
                        Vec3 wi = random_sphere(i, key + 2);
                        wi.z = -std::fabs(wi.z);
                        const Vec3 f = eval_bsdf(m, p, wo, wi);
                        for (int c = 0; c < 3; ++c) {
                            const double expected =
                                ref::rough_refraction(params(m, c), m.transmission, outside, to_dir(wo), to_dir(wi));
                            ASSERT_NEAR(f[c], expected, 1e-3 * expected + 1e-6)
                                << "r " << r << " m " << metallic << " ior " << ior << " outside " << outside
                                << " wo.z " << wo.z << " wi.z " << wi.z;
                        }
                        through += max_component(f) > 0 ? 1 : 0;
                    }
                    // Enough pairs compared (from inside, most are beyond
                    // what any facet refracts).
                    EXPECT_GT(through, outside ? 500 : 100);
                }
}

TEST(PbrRefraction, GeneralizedReciprocity) {
    // f carries η_o² (ωo's side), as a radiance BTDF does (Veach 1997, §5.2):
    // f(ωo → ωi)/η_o² = f(ωi → ωo)/η_i², here f_outside(ωo, ωi)/1 = f_inside(ωi, ωo)/ior².
    std::uint64_t key = 40;
    for (const float r : {0.2f, 0.6f}) {
        const Material m = volume({0.7f, 0.6f, 0.3f}, 0.2f, r, 0.8f);
        ++key;
        int compared = 0;
        for (std::uint32_t i = 0; i < 4000; ++i) {
            const Vec3 wo = random_sphere(i, key), wi = random_sphere(i, key + 100);
            if (wo.z <= 0 || wi.z >= 0) continue;
            const Vec3 a = eval_bsdf(m, kFlat, wo, wi), b = eval_bsdf(m, kBelowInside, wi, wo) / (1.5f * 1.5f);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-4f * a[c] + 1e-7f) << wo.z << " " << wi.z;
            compared += max_component(a) > 0 ? 1 : 0;
        }
        EXPECT_GT(compared, 100);
    }
}

TEST(PbrRefraction, WeightIsFCosOverPdf) {
    std::uint64_t key = 60;
    for (const float r : {0.1f, 0.4f, 0.8f})
        for (const bool outside : {true, false})
            for (const double theta : {10.0, 50.0, 80.0}) {
                const Material m = volume({0.9f, 0.7f, 0.4f}, 0.1f, r, 0.8f);
                const BsdfPoint& p = outside ? kFlat : kFlatInside;
                const Vec3 wo = polar(theta, 0.5);
                ++key;
                int through = 0;
                for (std::uint32_t i = 0; i < 4000; ++i) {
                    BsdfSample s;
                    if (!sample_bsdf(m, p, wo, rnd(3 * i, key), rnd(3 * i + 1, key), rnd(3 * i + 2, key), s)) continue;
                    ASSERT_FALSE(s.delta);
                    ASSERT_EQ(s.transmission, s.wi.z < 0.0f);
                    EXPECT_EQ(s.pdf, pdf_bsdf(m, p, wo, s.wi));
                    const Vec3 e = eval_bsdf(m, p, wo, s.wi) * (std::fabs(s.wi.z) / s.pdf);
                    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], e[c], 1e-5f * std::max(1e-3f, e[c]));
                    through += s.transmission ? 1 : 0;
                }
                // Outside, 1 − P_s of the draws go through, less the facets' reflections.
                if (outside || theta < 30) {
                    EXPECT_GT(through, 800) << r << " " << theta;
                }
            }
}

TEST(PbrRefraction, TendsToTheSmoothRefraction) {
    // At α = 0.05² = 0.0025 the refracted directions hug Snell's, and the
    // transmitted albedo E[weight · 1{through}] = ∫ f_t |cos θ_i| dω_i is the
    // delta's (1 − m)·t·(1 − F)·c·η² up to O(α) (the facets' spread of F
    // and G1): 1 % covers it with room. The lobe choice is stratified (u_lobe
    // = (i + ½)/n), so that the estimate's noise, of near-constant weights,
    // is far smaller.
    for (const bool outside : {true, false})
        for (const double theta : {0.0, 30.0}) {
            const Material rough = volume({0.9f, 0.7f, 0.4f}, 0.1f, 0.05f, 0.8f);
            const Material smooth = volume({0.9f, 0.7f, 0.4f}, 0.1f, 0.0f, 0.8f);
            const BsdfPoint& p = outside ? kFlat : kFlatInside;
            const Vec3 wo = polar(theta, 0.3);
            // The delta's transmitted weight × its probability, and its direction.
            Vec3 smooth_albedo{0.0f}, snell{0.0f};
            for (std::uint32_t i = 0; i < 64; ++i) {
                BsdfSample s;
                if (sample_bsdf(smooth, p, wo, (static_cast<float>(i) + 0.5f) / 64, 0.5f, 0.5f, s) && s.transmission) {
                    smooth_albedo = s.weight * s.pdf;
                    snell = s.wi;
                }
            }
            ASSERT_GT(max_component(smooth_albedo), 0.0f);
            Vec3 sum{0.0f};
            const std::uint32_t n = 20000;
            std::uint32_t through = 0, near_snell = 0;
            for (std::uint32_t i = 0; i < n; ++i) {
                BsdfSample s;
                const float u_lobe = (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
                if (!sample_bsdf(rough, p, wo, u_lobe, rnd(2 * i, 90), rnd(2 * i + 1, 90), s) || !s.transmission)
                    continue;
                sum += s.weight;
                ++through;
                near_snell += dot(s.wi, snell) > std::cos(0.05f) ? 1 : 0;
            }
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(sum[c] / n, smooth_albedo[c], 0.01 * smooth_albedo[c]) << outside << " " << theta;
            // GGX's tail: a facet tilted by θ_h > 0.1 (which turns the ray by
            // up to 0.05 rad) has probability ≈ α²/tan²θ_h ≈ 6·10⁻⁴.
            EXPECT_GT(near_snell, 0.99 * through) << outside << " " << theta;
        }
}

TEST(PbrRefraction, InterfaceKeepsAtMostItsEnergy) {
    // White glass: the energy leaving an interface, reflected plus
    // refracted (a refraction's weight over its radiance scaling η²), is at
    // most what arrives; single scattering loses what masking blocks, more
    // at high roughness and grazing angles. 5σ of the weights' mean.
    for (const float r : {0.3f, 0.6f})
        for (const bool outside : {true, false})
            for (const double theta : {0.0, 40.0, 70.0, 85.0}) {
                const Material m = volume(Vec3{1.0f}, 0.0f, r, 1.0f);
                const BsdfPoint& p = outside ? kFlat : kFlatInside;
                const float eta2 = outside ? 1.0f / 2.25f : 2.25f;
                double sum = 0, sum2 = 0;
                const int n = 20000;
                for (std::uint32_t i = 0; i < n; ++i) {
                    BsdfSample s;
                    if (!sample_bsdf(m, p, polar(theta, 0.4), rnd(3 * i, 70), rnd(3 * i + 1, 70), rnd(3 * i + 2, 70),
                                     s))
                        continue;
                    const double e = s.transmission ? s.weight.x / eta2 : s.weight.x;
                    sum += e;
                    sum2 += e * e;
                }
                const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
                EXPECT_LT(mean, 1.0 + 5 * se) << r << " " << outside << " " << theta;
                EXPECT_GT(mean, 0.5) << r << " " << outside << " " << theta;
                if (std::getenv("SOMBRA_CHI2_VERBOSE"))
                    std::printf("r %.1f %s %.0f: energy kept %.4f\n", r, outside ? "outside" : "inside", theta, mean);
            }
}

// χ² of sample_bsdf against pdf_bsdf over the whole sphere (binned around n).
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
    EXPECT_TRUE(r.passed) << "r " << m.roughness << " outside " << p.outside << " wo.z " << wo.z << ": " << r.message;
    if (std::getenv("SOMBRA_CHI2_VERBOSE")) std::printf("%s\n", r.message.c_str());
    const double f = r.success_fraction;
    EXPECT_NEAR(r.pdf_integral, f, 5 * std::sqrt(f * (1 - f) / o.samples) + 2e-3) << r.message;
}

TEST(PbrRefraction, Chi2SamplingMatchesThePdfFromBothSides) {
    // From inside, 30° is below the critical angle (41.8°), 60° beyond it at
    // n but not at every facet.
    std::uint64_t seed = 900;
    for (const float r : {0.15f, 0.4f, 0.8f})
        for (const bool outside : {true, false})
            for (const double theta : {0.0, 30.0, outside ? 75.0 : 60.0})
                expect_chi2(volume({0.9f, 0.9f, 0.9f}, 0.0f, r, 1.0f), outside ? kFlat : kFlatInside,
                            polar(theta, -0.7), ++seed);
    // Part diffuse, part metal, coloured.
    expect_chi2(volume({0.9f, 0.6f, 0.3f}, 0.3f, 0.5f, 0.6f), kFlat, polar(40, 0.2), 950);
    expect_chi2(volume({0.9f, 0.6f, 0.3f}, 0.3f, 0.5f, 0.6f), kFlatInside, polar(25, 0.2), 951);
}

}  // namespace
}  // namespace sombra
