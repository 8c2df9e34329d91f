// The variance AOV (spec §25): each pixel's estimate s²/n of the variance of
// its mean, from its own samples. Unbiased (a z-test over many pixels fed
// samples of known variance), exact against the pixel's own samples traced
// one by one, +∞ below two samples, and the same for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <vector>

#include "io/scene_json/scene_file.h"
#include "render/accumulation.h"
#include "render/render.h"

namespace sombra {
namespace {

TEST(VarianceAov, IsUnbiasedForSamplesOfKnownVariance) {
    // Red ~ U[0, 1) (σ² = 1/12), green ~ 4·U[0, 1) (σ² = 16/12), blue constant.
    constexpr int kPixels = 4096, kSamples = 6;
    AovSet aovs;
    aovs.variance = true;
    Accumulation acc(kPixels, 1, false, aovs);
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int p = 0; p < kPixels; ++p)
        for (int k = 0; k < kSamples; ++k)
            acc.add(static_cast<std::size_t>(p), Vec3{u(rng), 4.0f * u(rng), 0.5f}, nullptr);
    const std::vector<float> v = acc.aov_images().variance;
    ASSERT_EQ(v.size(), 3u * kPixels);
    const double expected[2] = {1.0 / 12.0 / kSamples, 16.0 / 12.0 / kSamples};
    for (int c = 0; c < 2; ++c) {
        double sum = 0, squares = 0;
        for (int p = 0; p < kPixels; ++p) {
            sum += v[3 * p + c];
            squares += static_cast<double>(v[3 * p + c]) * v[3 * p + c];
        }
        const double mean = sum / kPixels;
        const double sd = std::sqrt((squares - kPixels * mean * mean) / (kPixels - 1));
        const double z = (mean - expected[c]) / (sd / std::sqrt(kPixels));
        EXPECT_LT(std::fabs(z), 4.0) << "channel " << c << ": mean " << mean << ", expected " << expected[c];
    }
    for (int p = 0; p < kPixels; ++p) ASSERT_EQ(v[3 * p + 2], 0.0f) << "a constant channel has no variance";
}

TEST(VarianceAov, IsInfiniteBelowTwoSamples) {
    AovSet aovs;
    aovs.variance = true;
    Accumulation acc(3, 1, false, aovs);
    acc.add(1, Vec3{1.0f}, nullptr);
    acc.add(2, Vec3{1.0f}, nullptr);
    acc.add(2, Vec3{3.0f}, nullptr);
    const std::vector<float> v = acc.aov_images().variance;
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(v[c], std::numeric_limits<float>::infinity()) << "no sample";
        EXPECT_EQ(v[3 + c], std::numeric_limits<float>::infinity()) << "one sample";
        EXPECT_EQ(v[6 + c], 1.0f) << "s² = 2, n = 2";
    }
}

TEST(VarianceAov, EqualsThePixelsOwnSamplesAndIgnoresTheThreadCount) {
    Diagnostics diag;
    const LoadedScene loaded =
        load_scene_file(std::filesystem::path(SOMBRA_SOURCE_DIR) / "scenes" / "cornell-box-path.json", diag);
    const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
    RenderSettings settings = loaded.settings;
    settings.width = 24;
    settings.height = 18;
    settings.spp = 8;
    RenderOutput outputs[2];
    for (int t = 0; t < 2; ++t) {
        RenderJob job = make_render_job(loaded.scene, accel, settings, t == 0 ? 1 : 2);
        job.aovs.variance = true;
        RenderProgress progress;
        outputs[t] = render_image(job, progress);
    }
    ASSERT_EQ(outputs[0].aovs.variance, outputs[1].aovs.variance);
    ASSERT_EQ(outputs[0].film.rgb, outputs[1].film.rgb);

    // Brute force in double over each pixel's samples, traced one by one.
    const RenderJob job = make_render_job(loaded.scene, accel, settings, 1);
    int checked = 0;
    for (int j = 0; j < settings.height; j += 3)
        for (int i = 0; i < settings.width; i += 3) {
            double sum[3] = {}, squares[3] = {};
            for (int k = 0; k < settings.spp; ++k) {
                RayCounters counters;
                SampleRecord record;
                const Vec3 x = trace_pixel_sample(job, i, j, k, counters, record);
                const double c[3] = {x.x, x.y, x.z};
                for (int ch = 0; ch < 3; ++ch) sum[ch] += c[ch], squares[ch] += c[ch] * c[ch];
            }
            const double n = settings.spp;
            for (int ch = 0; ch < 3; ++ch) {
                const double mean = sum[ch] / n;
                const double expected = std::max(0.0, squares[ch] - n * mean * mean) / (n - 1) / n;
                const float got = outputs[0].aovs.variance[3 * (j * settings.width + i) + ch];
                EXPECT_NEAR(got, expected, 1e-5 * expected + 1e-12)
                    << "pixel (" << i << ", " << j << ") channel " << ch;
            }
            ++checked;
        }
    EXPECT_EQ(checked, 48);
}

}  // namespace
}  // namespace sombra
