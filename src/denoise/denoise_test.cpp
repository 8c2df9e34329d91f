// The whole denoiser on synthetic images: what it must keep, and the
// weights explain shows.
#include "denoise/denoise.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "core/error.h"
#include "denoise/denoise_test_util.h"

namespace sombra {
namespace {

using test::clean_radiance;
using test::synthetic_layers;

double relative_mse(const std::vector<float>& image, int w, int h) {
    double sum = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const double ref = clean_radiance(x, y, c, w, h);
                const double d = image[3 * static_cast<std::size_t>(y * w + x) + c] - ref;
                sum += d * d / (ref * ref + 0.01);
            }
    return sum / (3.0 * w * h);
}

std::vector<float> mean_of_halves(const DenoiseLayers& l) {
    std::vector<float> m(l.color[0].size());
    for (std::size_t i = 0; i < m.size(); ++i) m[i] = 0.5f * (l.color[0][i] + l.color[1][i]);
    return m;
}

TEST(Denoise, AConstantImageStaysConstant) {
    DenoiseLayers layers = synthetic_layers(48, 40, 16, true);
    for (auto& half : layers.color) std::fill(half.begin(), half.end(), 0.6f);
    for (const float v : denoise_image(layers, 2)) EXPECT_NEAR(v, 0.6f, 1e-5f);
}

TEST(Denoise, ANoiseFreeImagePassesThrough) {
    const DenoiseLayers layers = synthetic_layers(48, 40, 16, false);
    const std::vector<float> out = denoise_image(layers, 2);
    for (std::size_t i = 0; i < out.size(); ++i) EXPECT_NEAR(out[i], layers.color[0][i], 1e-5f * (1 + out[i])) << i;
}

TEST(Denoise, RemovesNoiseAndKeepsTheLight) {
    const int w = 96, h = 80;
    const DenoiseLayers layers = synthetic_layers(w, h, 8, true);
    const std::vector<float> noisy = mean_of_halves(layers);
    const std::vector<float> out = denoise_image(layers, 2);
    const double before = relative_mse(noisy, w, h), after = relative_mse(out, w, h);
    EXPECT_LT(after, before / 8) << before << " → " << after;
    // The mean over the image and over each quarter (spec §25: 1 % and 2 %).
    for (int quarter = -1; quarter < 4; ++quarter) {
        double in_sum = 0, out_sum = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (quarter >= 0 && (x < w / 2) != (quarter % 2 == 0)) continue;
                if (quarter >= 0 && (y < h / 2) != (quarter < 2)) continue;
                for (int c = 0; c < 3; ++c) {
                    const std::size_t i = 3 * static_cast<std::size_t>(y * w + x) + c;
                    in_sum += noisy[i];
                    out_sum += out[i];
                    ASSERT_TRUE(std::isfinite(out[i]));
                    ASSERT_GE(out[i], 0.0f);
                }
            }
        EXPECT_NEAR(out_sum / in_sum, 1.0, quarter < 0 ? 0.01 : 0.02) << "quarter " << quarter;
    }
}

TEST(Denoise, SameBytesOnAnyThreadCount) {
    const DenoiseLayers layers = synthetic_layers(75, 66, 4, true, 3);
    EXPECT_EQ(denoise_image(layers, 1), denoise_image(layers, 3));
}

TEST(Denoise, StopsOnCancelAndIsUnchangedWithout) {
    const DenoiseLayers layers = synthetic_layers(75, 66, 4, true, 3);
    std::atomic<bool> cancel{false};
    EXPECT_EQ(denoise_image(layers, 2, &cancel), denoise_image(layers, 2));
    cancel = true;
    EXPECT_TRUE(denoise_image(layers, 2, &cancel).empty());
    // Cancelled while it runs (a viewer's restart): it gives up between tiles.
    const DenoiseLayers large = synthetic_layers(320, 240, 4, true, 5);
    cancel = false;
    std::thread canceller([&cancel] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        cancel = true;
    });
    const auto start = std::chrono::steady_clock::now();
    EXPECT_TRUE(denoise_image(large, 2, &cancel).empty());
    canceller.join();
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(3));
}

TEST(Denoise, ExplainedWeightsAddUpToOneAndToThePixel) {
    const int w = 70, h = 64;
    const DenoiseLayers layers = synthetic_layers(w, h, 4, true, 11);
    const std::vector<float> image = denoise_image(layers, 2);
    for (const auto& [x, y] : {std::pair{35, 30}, std::pair{0, 0}, std::pair{69, 63}, std::pair{34, 5}}) {
        const DenoisedPixel pixel = explain_denoised_pixel(layers, x, y, 2);
        ASSERT_FALSE(pixel.terms.empty());
        for (int c = 0; c < 3; ++c) {
            double total = 0, magnitude = 0;
            for (const DenoiseTerm& t : pixel.terms) {
                total += t.weight[c];
                magnitude += std::abs(t.weight[c] * t.raw[c]);
                EXPECT_EQ(t.raw[c], layers.color[t.half][3 * static_cast<std::size_t>(t.y * w + t.x) + c]);
            }
            EXPECT_NEAR(total, 1.0, 1e-4) << x << "," << y;
            EXPECT_NEAR(pixel.unclamped[c], image[3 * static_cast<std::size_t>(y * w + x) + c], 1e-4 * magnitude + 1e-6)
                << x << "," << y;
            EXPECT_EQ(pixel.value[c], image[3 * static_cast<std::size_t>(y * w + x) + c]);
        }
    }
}

TEST(Denoise, RefusesBrokenLayersInOneLine) {
    DenoiseLayers layers = synthetic_layers(8, 8, 4, true);
    layers.color[1][4] = std::numeric_limits<float>::quiet_NaN();
    try {
        check_denoise_layers(layers, "in.exr");
        FAIL() << "a NaN colour was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "in.exr: denoise.B.G: nan at pixel (1, 0) is not a colour from 0 to 1e12");
    }
    layers = synthetic_layers(8, 8, 4, true);
    layers.depth[0].resize(10);
    EXPECT_THROW(check_denoise_layers(layers, "in.exr"), Error);
    layers = synthetic_layers(8, 8, 4, true);
    layers.variance[0] = -1.0f;
    EXPECT_THROW(check_denoise_layers(layers, "in.exr"), Error);
    layers = synthetic_layers(8, 8, 4, true);
    layers.depth[1][3] = std::numeric_limits<float>::infinity();  // a half that hit nothing
    EXPECT_NO_THROW(check_denoise_layers(layers, "in.exr"));
}

}  // namespace
}  // namespace sombra
