// Light through a homogeneous medium: the closed forms, and z-tests (fixed
// seeds, the sample variance) that the free-flight estimator is unbiased
// for what reaches a segment's end and for what scatters along it, per
// channel, with spectral MIS over channels of different extinction.
#include "render/media/homogeneous_medium.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "render/sampler.h"

namespace sombra {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

Medium medium(Vec3 sigma_a, Vec3 sigma_s, Vec3 emission = Vec3{0.0f}) {
    Medium m;
    m.sigma_a = sigma_a;
    m.sigma_s = sigma_s;
    m.emission = emission;
    return m;
}

// A coloured medium: channels of different extinction, one with none.
const Medium kColoured = medium({0.2f, 1.0f, 0.0f}, {0.3f, 1.0f, 0.0f});

float channel(Vec3 v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }

// Mean and standard error, per channel, of f(sample i) over n samples.
template <class F>
void expect_mean(const F& f, std::uint32_t n, Vec3 expected, const char* what) {
    std::array<double, 3> sum{}, sum_sq{};
    for (std::uint32_t i = 0; i < n; ++i) {
        const Vec3 v = f(i);
        for (int c = 0; c < 3; ++c) {
            sum[c] += channel(v, c);
            sum_sq[c] += static_cast<double>(channel(v, c)) * channel(v, c);
        }
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / n, variance = std::max(0.0, (sum_sq[c] - n * mean * mean) / (n - 1));
        const double error = std::sqrt(variance / n);
        if (error == 0.0) {
            EXPECT_NEAR(mean, channel(expected, c), 1e-6) << what << " channel " << c;
        } else {
            EXPECT_LT(std::fabs(mean - channel(expected, c)) / error, 4.0)
                << what << " channel " << c << ": mean " << mean << ", expected " << channel(expected, c);
        }
    }
}

FreeFlight flight(const Medium& m, float end, std::uint32_t i, std::uint64_t seed) {
    return sample_homogeneous_free_flight(m, end, hash_to_unit(2 * i, seed), hash_to_unit(2 * i + 1, seed));
}

TEST(HomogeneousMedium, TransmittanceIsBeersLaw) {
    const Vec3 t = homogeneous_transmittance(kColoured, 2.0f);
    EXPECT_FLOAT_EQ(t.x, std::exp(-1.0f));
    EXPECT_FLOAT_EQ(t.y, std::exp(-4.0f));
    EXPECT_FLOAT_EQ(t.z, 1.0f);
    const Vec3 far = homogeneous_transmittance(kColoured, kInfinity);  // an unbounded medium hides what is far
    EXPECT_EQ(far.x, 0.0f);
    EXPECT_EQ(far.y, 0.0f);
    EXPECT_EQ(far.z, 1.0f);  // no extinction: all of it, not NaN
}

TEST(HomogeneousMedium, EmissionIsTheIntegralOfWhatReachesTheStart) {
    const Medium glow = medium({0.5f, 0.0f, 1e-6f}, {1.0f, 0.0f, 0.0f}, {2.0f, 3.0f, 4.0f});
    const float d = 1.7f;
    // The midpoint rule, summed in double, against the closed form.
    std::array<double, 3> sum{};
    constexpr int steps = 100000;
    for (int i = 0; i < steps; ++i) {
        const float s = (static_cast<float>(i) + 0.5f) * d / steps;
        const Vec3 v = homogeneous_transmittance(glow, s) * glow.emission * (d / steps);
        for (int c = 0; c < 3; ++c) sum[c] += channel(v, c);
    }
    const Vec3 e = homogeneous_emission(glow, d);
    EXPECT_NEAR(e.x, sum[0], 1e-4 * sum[0]);
    EXPECT_NEAR(e.y, 3.0f * d, 1e-5f);  // no extinction: ε·d
    EXPECT_NEAR(e.z, sum[2], 1e-4 * sum[2]);
    EXPECT_EQ(max_component(homogeneous_emission(kColoured, d)), 0.0f);
}

TEST(HomogeneousMedium, WhatReachesTheEndIsTheTransmittanceInExpectation) {
    for (const float end : {0.3f, 2.0f, 7.0f}) {
        expect_mean(
            [&](std::uint32_t i) {
                const FreeFlight f = flight(kColoured, end, i, 11);
                return f.scattered ? Vec3{0.0f} : f.weight;
            },
            200000, homogeneous_transmittance(kColoured, end), "reaching the end");
    }
}

TEST(HomogeneousMedium, WhatScattersIsTheScatteringIntegralInExpectation) {
    // E[weight · h(t)] over scattering events = ∫₀ᵉⁿᵈ T(t)·σ_s·h(t) dt; with
    // h = 1 that is σ_s (1 − exp(−σ_t end))/σ_t, and with h(t) = t checked
    // against the midpoint rule.
    const Vec3 sigma_t = extinction(kColoured);
    for (const float end : {0.3f, 2.0f, kInfinity}) {
        Vec3 expected{0.0f};
        for (int c = 0; c < 3; ++c) {
            const double st = channel(sigma_t, c), ss = channel(kColoured.sigma_s, c);
            const double value = st > 0 ? ss * (std::isinf(end) ? 1.0 : -std::expm1(-st * end)) / st : 0.0;
            (c == 0 ? expected.x : c == 1 ? expected.y : expected.z) = static_cast<float>(value);
        }
        expect_mean(
            [&](std::uint32_t i) {
                const FreeFlight f = flight(kColoured, end, i, 23);
                if (f.scattered) {
                    EXPECT_GE(f.t, 0.0f);
                    EXPECT_LT(f.t, end);
                }
                return f.scattered ? f.weight : Vec3{0.0f};
            },
            200000, expected, "scattering");
    }
    const float end = 3.0f;
    Vec3 expected{0.0f};
    constexpr int steps = 20000;
    for (int i = 0; i < steps; ++i) {
        const float t = (static_cast<float>(i) + 0.5f) * end / steps;
        expected += homogeneous_transmittance(kColoured, t) * kColoured.sigma_s * (t * end / steps);
    }
    expect_mean(
        [&](std::uint32_t i) {
            const FreeFlight f = flight(kColoured, end, i, 37);
            return f.scattered ? f.weight * f.t : Vec3{0.0f};
        },
        200000, expected, "scattering, weighted by t");
}

TEST(HomogeneousMedium, AVacuumNeverInteracts) {
    const Medium vacuum = medium(Vec3{0.0f}, Vec3{0.0f});
    for (std::uint32_t i = 0; i < 100; ++i) {
        const FreeFlight f = flight(vacuum, kInfinity, i, 3);
        EXPECT_FALSE(f.scattered);
        EXPECT_EQ(f.weight.x, 1.0f);
        EXPECT_EQ(f.weight.z, 1.0f);
    }
}

}  // namespace
}  // namespace sombra
