// The Henyey–Greenstein phase function: its closed forms, its sampling
// against its density (χ²), and its mean cosine, which is g (z-tests).
#include "render/media/phase_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>

#include "core/frame.h"
#include "render/chi2_test_util.h"
#include "render/sampler.h"

namespace sombra {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kAsymmetries[] = {-0.9f, -0.3f, 0.0f, 0.5f, 0.95f};
constexpr int kChi2Tests = static_cast<int>(std::size(kAsymmetries));

const Vec3 kIn = normalize(Vec3{0.3f, -0.5f, 0.8f});

PhaseSample draw(float g, std::uint32_t i, std::uint64_t seed) {
    return sample_henyey_greenstein(g, kIn, hash_to_unit(2 * i, seed), hash_to_unit(2 * i + 1, seed));
}

TEST(HenyeyGreenstein, MatchesItsClosedForms) {
    for (const float c : {-1.0f, -0.2f, 0.0f, 0.7f, 1.0f})
        EXPECT_NEAR(henyey_greenstein(0.0f, c), 1.0 / (4 * kPi), 1e-8);
    for (const float g : kAsymmetries) {
        const double gd = g;
        // Straight on and straight back: (1 ± g) / (4π (1 ∓ g)²).
        EXPECT_NEAR(henyey_greenstein(g, 1.0f), (1 + gd) / (4 * kPi * (1 - gd) * (1 - gd)), 1e-5 * (1 + 1 / (1 - gd)));
        EXPECT_NEAR(henyey_greenstein(g, -1.0f), (1 - gd) / (4 * kPi * (1 + gd) * (1 + gd)), 1e-5 * (1 + 1 / (1 + gd)));
    }
}

TEST(HenyeyGreenstein, SamplesItsOwnDensity) {
    for (const float g : kAsymmetries) {
        const auto seed = static_cast<std::uint64_t>(1000 + 100 * g);
        const auto sample = [&](std::uint32_t i) -> std::optional<Vec3> { return draw(g, i, seed).out; };
        const auto pdf = [&](Vec3 out) { return henyey_greenstein(g, dot(kIn, out)); };
        chi2::Options o;
        o.test_count = kChi2Tests;
        const chi2::Result r = chi2::run(Frame::from_normal(kIn), sample, pdf, o);
        EXPECT_TRUE(r.passed) << "g " << g << ": " << r.message;
        EXPECT_NEAR(r.pdf_integral, 1.0, 2e-3) << "g " << g;
        EXPECT_EQ(r.success_fraction, 1.0);
    }
}

TEST(HenyeyGreenstein, ASampleCarriesItsDensity) {
    for (const float g : kAsymmetries)
        for (std::uint32_t i = 0; i < 1000; ++i) {
            const PhaseSample s = draw(g, i, 7);
            EXPECT_NEAR(length(s.out), 1.0f, 1e-5f);
            EXPECT_NEAR(s.pdf, henyey_greenstein(g, dot(kIn, s.out)), 1e-5f * s.pdf) << "g " << g << " sample " << i;
        }
}

TEST(HenyeyGreenstein, TheMeanCosineIsG) {
    // E[cos θ] = g; the sample mean against it in units of its standard error.
    constexpr std::uint32_t n = 200000;
    for (const float g : kAsymmetries) {
        double sum = 0, sum_sq = 0;
        for (std::uint32_t i = 0; i < n; ++i) {
            const double c = dot(kIn, draw(g, i, 99).out);
            sum += c;
            sum_sq += c * c;
        }
        const double mean = sum / n, variance = (sum_sq - n * mean * mean) / (n - 1);
        const double z = (mean - g) / std::sqrt(variance / n);
        EXPECT_LT(std::fabs(z), 4.0) << "g " << g << ": mean cosine " << mean;
    }
}

TEST(HenyeyGreenstein, NearlyIsotropicIsContinuous) {
    // Below |g| = 1e-4 the isotropic inverse takes over: no jump at the switch.
    for (std::uint32_t i = 0; i < 100; ++i) {
        const float u1 = hash_to_unit(i, 5), u2 = hash_to_unit(i, 6);
        const Vec3 a = sample_henyey_greenstein(0.0f, kIn, u1, u2).out;
        const Vec3 b = sample_henyey_greenstein(2e-4f, kIn, u1, u2).out;
        EXPECT_LT(length(a - b), 1e-3f) << i;
    }
}

}  // namespace
}  // namespace sombra
