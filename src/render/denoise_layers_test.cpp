// The denoiser's layers as the render gathers them (spec §25): samples
// split by index parity into the half buffers, whose difference estimates
// the variance of the pixel's mean as the samples' own variance does.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "render/accumulation.h"

namespace sombra {
namespace {

TEST(DenoiseLayers, HalvesHoldTheEvenAndTheOddSamples) {
    AovSet aovs;
    aovs.denoise = true;
    Accumulation acc(2, 1, false, aovs);
    FirstHit hit;
    hit.hit = true;
    hit.albedo = {0.5f, 0.25f, 1.0f};
    hit.normal = {0.0f, 1.0f, 0.0f};
    hit.depth = 2.0f;
    for (int k = 0; k < 5; ++k) acc.add(0, Vec3{static_cast<float>(k), 1.0f, 0.0f}, k == 1 ? nullptr : &hit);
    acc.add(1, Vec3{3.0f, 3.0f, 3.0f}, nullptr);  // one sample, a miss
    const DenoiseLayers layers = acc.aov_images().denoise;
    EXPECT_EQ(layers.width, 2);
    EXPECT_EQ(layers.color[0][0], (0.0f + 2.0f + 4.0f) / 3.0f);  // samples 0, 2, 4
    EXPECT_EQ(layers.color[1][0], (1.0f + 3.0f) / 2.0f);         // samples 1, 3
    EXPECT_EQ(layers.albedo[1][0], 0.25f);                       // sample 1 missed: (0 + 0.5) / 2
    EXPECT_EQ(layers.depth[1][0], 2.0f);                         // the mean over the half's hits
    EXPECT_EQ(layers.normal[0][1], 1.0f);
    // A pixel of one sample: half B takes half A's values; its variance is unknown.
    EXPECT_EQ(layers.color[1][3], 3.0f);
    EXPECT_EQ(layers.depth[0][1], std::numeric_limits<float>::infinity());
    EXPECT_EQ(layers.variance[3], std::numeric_limits<float>::infinity());
}

TEST(DenoiseLayers, HalfBufferDifferenceAgreesWithTheSampleVariance) {
    // For n samples split n/2 and n/2, E[(A − B)²/4] = σ²/n = E[s²/n]: the
    // two estimates of the mean's variance differ by 0 in expectation. A
    // z-test over many pixels of exponential samples (σ = the mean).
    constexpr int kPixels = 8192, kSamples = 8;
    AovSet aovs;
    aovs.denoise = true;
    Accumulation acc(kPixels, 1, false, aovs);
    std::mt19937 rng(2025);
    std::exponential_distribution<float> e(1.0f);
    for (int p = 0; p < kPixels; ++p) {
        const float scale = 0.5f + static_cast<float>(p % 7);
        for (int k = 0; k < kSamples; ++k)
            acc.add(static_cast<std::size_t>(p), Vec3{scale * e(rng), e(rng), 2.0f}, nullptr);
    }
    const DenoiseLayers layers = acc.aov_images().denoise;
    for (int c = 0; c < 2; ++c) {
        double sum = 0, squares = 0;
        for (int p = 0; p < kPixels; ++p) {
            const std::size_t i = 3 * static_cast<std::size_t>(p) + static_cast<std::size_t>(c);
            const double half = layers.color[0][i] - layers.color[1][i];
            const double d = half * half / 4.0 - layers.variance[i];
            sum += d;
            squares += d * d;
        }
        const double mean = sum / kPixels;
        const double standard_error = std::sqrt((squares / kPixels - mean * mean) / (kPixels - 1));
        EXPECT_LT(std::abs(mean / standard_error), 4.0) << "channel " << c << ": mean difference " << mean;
    }
    // A constant channel: both estimates are 0.
    EXPECT_EQ(layers.color[0][2], layers.color[1][2]);
    EXPECT_EQ(layers.variance[2], 0.0f);
}

}  // namespace
}  // namespace sombra
