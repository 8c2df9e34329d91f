// Non-local-means weights against their definition computed directly.
#include "denoise/nl_means.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "denoise/denoise_test_util.h"

namespace sombra {
namespace {

using test::random_raster;

// The weight of q = p + (dx, dy) for p, from the definition in doubles.
double direct_weight(const Raster& g, const Raster& var, int px, int py, int dx, int dy, const NlMeansParams& params) {
    const int qx = px + dx, qy = py + dy;
    if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) return 0.0;
    double sum = 0;
    int count = 0;
    for (int sy = -params.patch_radius; sy <= params.patch_radius; ++sy)
        for (int sx = -params.patch_radius; sx <= params.patch_radius; ++sx) {
            const int ax = px + sx, ay = py + sy, bx = qx + sx, by = qy + sy;
            if (ax < 0 || ay < 0 || ax >= g.width || ay >= g.height) continue;
            if (bx < 0 || by < 0 || bx >= g.width || by >= g.height) continue;
            double d = 0;
            for (int c = 0; c < g.channels; ++c) {
                const double diff = g.at(ax, ay)[c] - g.at(bx, by)[c];
                const double va = var.at(ax, ay)[c], vb = var.at(bx, by)[c];
                d += (diff * diff - (va + std::min(va, vb))) / (1e-10 + params.k * params.k * (va + vb));
            }
            sum += d / g.channels;
            ++count;
        }
    return std::exp(-std::max(0.0, sum / count));
}

TEST(NlMeans, TileWeightsMatchTheDefinition) {
    const NlMeansParams params{4, 2, 0.7f};
    const Raster guide = random_raster(13, 11, 3, 0.0f, 1.0f, 1);
    const Raster variance = random_raster(13, 11, 3, 0.01f, 0.2f, 2);
    std::vector<float> weights, scratch;
    const PixelRect centres{2, 1, 12, 9};
    const int side = window_side(params);
    for (const int stride : {1, 2, 3}) {
        nl_means_tile_weights(guide, variance, centres, stride, params, weights, scratch);
        const int nx = strided_count(centres.width(), stride);
        ASSERT_EQ(weights.size(), static_cast<std::size_t>(nx * strided_count(centres.height(), stride) * side * side));
        for (int y = centres.y0; y < centres.y1; y += stride)
            for (int x = centres.x0; x < centres.x1; x += stride)
                for (int dy = -4; dy <= 4; ++dy)
                    for (int dx = -4; dx <= 4; ++dx) {
                        const auto c =
                            static_cast<std::size_t>((y - centres.y0) / stride) * static_cast<std::size_t>(nx) +
                            static_cast<std::size_t>((x - centres.x0) / stride);
                        const float w = weights[c * static_cast<std::size_t>(window_offsets(params)) +
                                                static_cast<std::size_t>((dy + 4) * side + dx + 4)];
                        EXPECT_NEAR(w, direct_weight(guide, variance, x, y, dx, dy, params), 2e-5)
                            << x << "," << y << " offset " << dx << "," << dy << " stride " << stride;
                    }
    }
}

TEST(NlMeans, APixelsWeightDoesNotDependOnItsTile) {
    // explain recomputes a few tiles only: a pixel must get the same bytes
    // whichever rectangle it was computed in.
    const NlMeansParams params{5, 3, 0.5f};
    const Raster guide = random_raster(40, 37, 3, 0.0f, 2.0f, 3);
    const Raster variance = random_raster(40, 37, 3, 0.0f, 0.1f, 4);
    std::vector<float> whole, single, strided, scratch;
    const PixelRect all{0, 0, 40, 37};
    nl_means_tile_weights(guide, variance, all, 1, params, whole, scratch);
    nl_means_tile_weights(guide, variance, PixelRect{17, 30, 18, 31}, 1, params, single, scratch);
    // (17, 30) is the 8th of 15 centres across in row 15 with a stride of 2 from (1, 0).
    nl_means_tile_weights(guide, variance, PixelRect{1, 0, 31, 37}, 2, params, strided, scratch);
    const auto offsets = static_cast<std::size_t>(window_offsets(params));
    const std::size_t c = 30 * 40 + 17, c_strided = 15 * 15 + 8;
    for (std::size_t o = 0; o < offsets; ++o) {
        EXPECT_EQ(whole[c * offsets + o], single[o]) << o;
        EXPECT_EQ(whole[c * offsets + o], strided[c_strided * offsets + o]) << o;
    }
}

TEST(NlMeans, APixelWeighsItselfOne) {
    const NlMeansParams params{3, 2, 0.5f};
    const Raster guide = random_raster(9, 9, 1, 0.0f, 1.0f, 5);
    const Raster variance = random_raster(9, 9, 1, 0.0f, 0.1f, 6);
    std::vector<float> weights, scratch;
    nl_means_tile_weights(guide, variance, PixelRect{0, 0, 9, 9}, 1, params, weights, scratch);
    const std::size_t centre_offset = 3 * static_cast<std::size_t>(window_side(params)) + 3;
    for (std::size_t c = 0; c < 81; ++c)
        EXPECT_EQ(weights[c * static_cast<std::size_t>(window_offsets(params)) + centre_offset], 1.0f);
    for (const float w : weights) {
        EXPECT_GE(w, 0.0f);
        EXPECT_LE(w, 1.0f);
    }
}

TEST(NlMeans, FilterKeepsAConstantAndIsTheSameOnAnyThreadCount) {
    const NlMeansParams params{5, 3, 1.0f};
    const Raster guide = random_raster(70, 45, 3, 0.0f, 1.0f, 7);
    const Raster variance = random_raster(70, 45, 3, 0.0f, 0.3f, 8);
    const Raster constant(70, 45, 3, 0.25f);
    for (const float v : nl_means_filter(constant, guide, variance, params, 2).values) EXPECT_NEAR(v, 0.25f, 1e-6f);
    const Raster values = random_raster(70, 45, 3, 0.0f, 5.0f, 9);
    EXPECT_EQ(nl_means_filter(values, guide, variance, params, 1).values,
              nl_means_filter(values, guide, variance, params, 3).values);
}

}  // namespace
}  // namespace sombra
