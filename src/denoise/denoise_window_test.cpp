// The denoiser is local (spec §27's --crop with --denoise): a window of the
// image, grown by denoise_source_rect, denoised alone gives the window's
// pixels bit for bit as the whole image does, misses and unknown variances
// included.
#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <vector>

#include "denoise/denoise.h"
#include "denoise/denoise_test_util.h"

namespace sombra {
namespace {

using test::synthetic_layers;

// Synthetic layers with what a real render has beside its noise: a sky (no
// hit: infinite depth, zero features) in the top rows' left part, pixels
// of one sample (infinite variance) scattered, depth growing along x.
DenoiseLayers layers_with_sky(int width, int height) {
    DenoiseLayers layers = synthetic_layers(width, height, 4, true, 11);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t p =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
            const bool sky = y < height / 4 && x < 2 * width / 3;
            for (int h = 0; h < 2; ++h) {
                layers.depth[h][p] =
                    sky ? std::numeric_limits<float>::infinity() : 2.0f + 0.05f * static_cast<float>(x);
                if (sky)
                    for (int c = 0; c < 3; ++c) layers.albedo[h][3 * p + c] = layers.normal[h][3 * p + c] = 0.0f;
            }
            if ((x * 7 + y * 13) % 29 == 0)
                for (int c = 0; c < 3; ++c) layers.variance[3 * p + c] = std::numeric_limits<float>::infinity();
        }
    return layers;
}

DenoiseLayers cut(const DenoiseLayers& l, PixelRect r) {
    DenoiseLayers out;
    out.width = r.width();
    out.height = r.height();
    const auto take = [&](const std::vector<float>& values, std::size_t channels) {
        std::vector<float> kept;
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x)
                for (std::size_t c = 0; c < channels; ++c)
                    kept.push_back(values[(static_cast<std::size_t>(y) * static_cast<std::size_t>(l.width) +
                                           static_cast<std::size_t>(x)) *
                                              channels +
                                          c]);
        return kept;
    };
    out.variance = take(l.variance, 3);
    for (int h = 0; h < 2; ++h) {
        out.color[h] = take(l.color[h], 3);
        out.albedo[h] = take(l.albedo[h], 3);
        out.normal[h] = take(l.normal[h], 3);
        out.depth[h] = take(l.depth[h], 1);
    }
    return out;
}

// The pixels of `kept` in an image denoised over `area` (3 floats a pixel).
std::vector<float> pixels_of(const std::vector<float>& image, PixelRect area, PixelRect kept) {
    std::vector<float> out;
    for (int y = kept.y0; y < kept.y1; ++y)
        for (int x = kept.x0; x < kept.x1; ++x)
            for (int c = 0; c < 3; ++c)
                out.push_back(image[(static_cast<std::size_t>(y - area.y0) * static_cast<std::size_t>(area.width()) +
                                     static_cast<std::size_t>(x - area.x0)) *
                                        3 +
                                    static_cast<std::size_t>(c)]);
    return out;
}

TEST(DenoiseWindow, AGrownWindowGivesTheWholeImagesPixels) {
    const int w = 270, h = 230;
    const DenoiseLayers layers = layers_with_sky(w, h);
    const PixelRect whole{0, 0, w, h};
    const std::vector<float> full = denoise_image(layers, 2);
    // Inside, at the sky's edge, on the right and bottom sides, one pixel.
    for (const PixelRect kept : {PixelRect{131, 101, 151, 117}, PixelRect{150, 40, 190, 80},
                                 PixelRect{230, 190, 270, 230}, PixelRect{77, 3, 78, 4}}) {
        const PixelRect source = denoise_source_rect(kept, w, h);
        SCOPED_TRACE(testing::Message() << "kept " << kept.x0 << "," << kept.y0 << " source " << source.x0 << ","
                                        << source.y0 << "-" << source.x1 << "," << source.y1);
        EXPECT_EQ(source.x0 % kDenoiseAlign, 0);
        EXPECT_EQ(source.y0 % kDenoiseAlign, 0);
        EXPECT_LE(source.x0, kept.x0 - denoise_reach() < 0 ? 0 : kept.x0 - denoise_reach());
        const std::vector<float> alone = denoise_image(cut(layers, source), 1);
        EXPECT_EQ(pixels_of(alone, source, kept), pixels_of(full, whole, kept));
    }
}

TEST(DenoiseWindow, TheReachIsNeeded) {
    // The same window with too small a margin differs: the test above can fail.
    const int w = 270, h = 230;
    const DenoiseLayers layers = layers_with_sky(w, h);
    const PixelRect kept{150, 40, 190, 80};
    const PixelRect near{128, 0, 212, 102};  // an aligned corner, 22 pixels of margin
    EXPECT_NE(pixels_of(denoise_image(cut(layers, near), 2), near, kept),
              pixels_of(denoise_image(layers, 2), {0, 0, w, h}, kept));
}

}  // namespace
}  // namespace sombra
