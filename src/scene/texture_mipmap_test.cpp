// Mip pyramids (scene/texture_mipmap.h): levels are the box averages of the
// level above, worked out by hand on tiny textures with exact values; odd
// sides weight their shared texels by the share each output covers; the
// pyramid's size stays within a third of the texture's; lookups blend the two
// levels around λ and are the bilinear lookup itself at λ <= 0.
#include "scene/texture_mipmap.h"

#include "scene/material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace sombra {
namespace {

// A texture of width × height texels with `channels` values each, TOP row first.
Texture make_texture(int width, int height, int channels, std::vector<float> values) {
    Texture t;
    t.source = "test";
    t.encoding = TextureEncoding::Data;
    t.width = width;
    t.height = height;
    t.channels = channels;
    t.texels = std::move(values);
    return t;
}

TEST(MipPyramid, LevelsAreTheAveragesOfTwoByTwoBlocks) {
    // 4 × 4, grey + alpha: grey 0 … 15 row by row from the top, alpha twice grey.
    std::vector<float> values;
    for (int i = 0; i < 16; ++i) values.insert(values.end(), {static_cast<float>(i), 2.0f * static_cast<float>(i)});
    Texture t = make_texture(4, 4, 2, values);
    build_mip_pyramid(t);
    ASSERT_EQ(t.mip_levels.size(), 2u) << "4 x 4 -> 2 x 2 -> 1 x 1";
    const TextureLevel& one = t.mip_levels[0];
    ASSERT_EQ(one.width, 2);
    ASSERT_EQ(one.height, 2);
    // Top-left block {0, 1, 4, 5}: 2.5; top-right {2, 3, 6, 7}: 4.5; then 10.5 and 12.5.
    EXPECT_EQ(one.texels, (std::vector<float>{2.5f, 5.0f, 4.5f, 9.0f, 10.5f, 21.0f, 12.5f, 25.0f}));
    const TextureLevel& two = t.mip_levels[1];
    ASSERT_EQ(two.width, 1);
    ASSERT_EQ(two.height, 1);
    EXPECT_EQ(two.texels, (std::vector<float>{7.5f, 15.0f}));
}

TEST(MipPyramid, OddSidesShareTheirMiddleTexelsByTheAreaEachOutputCovers) {
    // 5 × 3 → 2 × 1 (then the shorter side is 1: no more levels). Along x the
    // two outputs cover input columns [0, 2.5) and [2.5, 5): weights 2/5, 2/5,
    // 1/5 and 1/5, 2/5, 2/5; along y the one output covers the three rows, 1/3 each.
    const std::vector<float> rows[3] = {{1, 2, 3, 4, 5}, {10, 20, 30, 40, 50}, {100, 200, 300, 400, 500}};
    std::vector<float> values;
    for (const auto& r : rows) values.insert(values.end(), r.begin(), r.end());
    Texture t = make_texture(5, 3, 1, values);
    build_mip_pyramid(t);
    ASSERT_EQ(t.mip_levels.size(), 1u);
    ASSERT_EQ(t.mip_levels[0].width, 2);
    ASSERT_EQ(t.mip_levels[0].height, 1);
    // Each row's sum is 111 × its first-row value: the weights apply to 1 + 10 + 100 = 111.
    const double left = 111.0 * (0.4 * 1 + 0.4 * 2 + 0.2 * 3) / 3.0;
    const double right = 111.0 * (0.2 * 3 + 0.4 * 4 + 0.4 * 5) / 3.0;
    EXPECT_FLOAT_EQ(t.mip_levels[0].texels[0], static_cast<float>(left));
    EXPECT_FLOAT_EQ(t.mip_levels[0].texels[1], static_cast<float>(right));
}

TEST(MipPyramid, EveryLevelKeepsTheTexturesMean) {
    // 37 × 23, three channels of unrelated values: each output texel covers
    // the same area of the level above, so every level's mean is the base's.
    std::vector<float> values;
    std::uint32_t state = 12345;
    for (int i = 0; i < 37 * 23 * 3; ++i) {
        state = state * 1664525u + 1013904223u;
        values.push_back(static_cast<float>(state >> 8) / static_cast<float>(1u << 24));
    }
    Texture t = make_texture(37, 23, 3, values);
    build_mip_pyramid(t);
    const auto mean = [](const std::vector<float>& v, int channel) {
        double sum = 0;
        for (std::size_t i = static_cast<std::size_t>(channel); i < v.size(); i += 3) sum += v[i];
        const std::size_t texels = v.size() / 3;
        return sum / static_cast<double>(texels);
    };
    ASSERT_EQ(t.mip_levels.size(), 4u) << "37 x 23 -> 18 x 11 -> 9 x 5 -> 4 x 2 -> 2 x 1";
    for (int c = 0; c < 3; ++c)
        for (const TextureLevel& level : t.mip_levels)
            // Float texels rounded once each: the means agree to float precision.
            EXPECT_NEAR(mean(level.texels, c), mean(t.texels, c), 1e-6) << level.width << " x " << level.height;
}

TEST(MipPyramid, CostsAtMostAThirdOfTheTexture) {
    const auto check = [](int width, int height) {
        Texture t =
            make_texture(width, height, 1,
                         std::vector<float>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 1.0f));
        build_mip_pyramid(t);
        std::size_t levels = 0;
        int w = width, h = height;
        for (const TextureLevel& l : t.mip_levels) {
            EXPECT_EQ(l.width, w / 2);
            EXPECT_EQ(l.height, h / 2);
            w = l.width;
            h = l.height;
            levels += l.texels.size();
        }
        EXPECT_EQ(std::min(w, h), 1) << width << " x " << height << ": the pyramid stops where the shorter side is 1";
        EXPECT_LE(3 * levels, t.texels.size()) << width << " x " << height;
    };
    for (int w = 1; w <= 40; ++w)
        for (int h = 1; h <= 40; ++h) check(w, h);
    check(4096, 16);
    check(1, 1000);
    check(1000, 3);
}

TEST(MipPyramid, TableBuildsEachTextureAsAlone) {
    std::vector<Texture> table;
    for (int k = 1; k <= 6; ++k) {
        const int w = 16 * k + 3, h = 8 * k + 1;
        std::vector<float> v(static_cast<std::size_t>(w * h * 4));
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>((i * 7919u) % 251u) / 250.0f;
        table.push_back(make_texture(w, h, 4, v));
    }
    std::vector<Texture> alone = table;
    build_mip_pyramids(table);
    for (std::size_t i = 0; i < table.size(); ++i) {
        build_mip_pyramid(alone[i]);
        ASSERT_EQ(table[i].mip_levels.size(), alone[i].mip_levels.size());
        for (std::size_t l = 0; l < table[i].mip_levels.size(); ++l)
            EXPECT_EQ(table[i].mip_levels[l].texels, alone[i].mip_levels[l].texels);
    }
}

TEST(MipLookup, LodCountsTexelsAcrossTheFootprint) {
    const Texture t = make_texture(256, 64, 1, std::vector<float>(256 * 64, 0.0f));
    // √(256 · 64) = 128 texels per uv unit: 1/32 of uv is 4 texels, λ = 2.
    EXPECT_FLOAT_EQ(mip_lod(t, 1.0f / 32.0f), 2.0f);
    EXPECT_FLOAT_EQ(mip_lod(t, 1.0f / 128.0f), 0.0f);
    EXPECT_FLOAT_EQ(mip_lod(t, 1.0f / 256.0f), -1.0f);
}

TEST(MipLookup, TrilinearBlendsTheTwoLevelsAroundLod) {
    // 8 × 8 of unrelated values: levels 4 × 4, 2 × 2, 1 × 1.
    std::vector<float> values;
    for (int i = 0; i < 64; ++i) values.push_back(static_cast<float>((i * 37) % 64) / 8.0f);
    Texture t = make_texture(8, 8, 1, values);
    const Texture bare = t;
    build_mip_pyramid(t);
    ASSERT_EQ(t.mip_levels.size(), 3u);
    const auto level = [&t](std::size_t l, Vec2 uv) {
        const TextureLevel& m = t.mip_levels[l - 1];
        return eval_texels(m.texels.data(), m.width, m.height, 1, uv, TextureWrap::Repeat, TextureWrap::Repeat)[0];
    };
    const Vec2 points[] = {{0.3f, 0.7f}, {0.05f, 0.95f}, {0.5f, 0.5f}, {-1.2f, 3.4f}};
    for (const Vec2 uv : points) {
        const float base = eval_texture(t, uv)[0];
        // λ <= 0, NaN, or no pyramid: the full-resolution lookup, bit for bit.
        EXPECT_EQ(eval_texture_lod(t, uv, 0.0f)[0], base);
        EXPECT_EQ(eval_texture_lod(t, uv, -3.0f)[0], base);
        EXPECT_EQ(eval_texture_lod(t, uv, std::numeric_limits<float>::quiet_NaN())[0], base);
        EXPECT_EQ(eval_texture_lod(bare, uv, 2.0f)[0], base);
        // Between levels: the blend of the two around λ.
        EXPECT_FLOAT_EQ(eval_texture_lod(t, uv, 0.25f)[0], 0.75f * base + 0.25f * level(1, uv));
        EXPECT_FLOAT_EQ(eval_texture_lod(t, uv, 1.5f)[0], 0.5f * level(1, uv) + 0.5f * level(2, uv));
        EXPECT_FLOAT_EQ(eval_texture_lod(t, uv, 2.0f)[0], level(2, uv));
        // At or past the coarsest level: the coarsest level, the texture's mean.
        EXPECT_FLOAT_EQ(eval_texture_lod(t, uv, 3.0f)[0], level(3, uv));
        EXPECT_FLOAT_EQ(eval_texture_lod(t, uv, std::numeric_limits<float>::infinity())[0], level(3, uv));
    }
    float mean = 0;
    for (float v : values) mean += v;
    EXPECT_FLOAT_EQ(eval_texture_lod(t, {0.3f, 0.7f}, 7.0f)[0], mean / 64.0f);
}

TEST(MipLookup, TransformedReferencesMoveUvAndScaleTheFootprint) {
    // A reference with KHR_texture_transform's scale 2 (uv' = 2·uv + offset)
    // reads the pyramid at uv' and a footprint twice as wide in the image.
    std::vector<float> values;
    for (int i = 0; i < 64; ++i) values.push_back(static_cast<float>((i * 29) % 64) / 8.0f);
    std::vector<Texture> table{make_texture(8, 8, 1, values)};
    build_mip_pyramid(table[0]);
    TextureRef ref;
    ref.texture = 0;
    ref.transformed = true;
    ref.uv_transform = UvTransform{2, 0, 0.25f, 0, 2, -0.5f};
    const Vec2 uv{0.3f, 0.45f}, moved = apply_uv_transform(ref.uv_transform, uv);
    EXPECT_NEAR(moved.x, 0.85f, 1e-6f);
    EXPECT_NEAR(moved.y, 0.4f, 1e-6f);
    const float footprint = 0.3f;
    EXPECT_EQ(eval_texture_ref_filtered(table, ref, uv, footprint)[0],
              eval_texture_lod(table[0], moved, mip_lod(table[0], 2 * footprint))[0]);
    // Footprint 0: the unfiltered transformed lookup, bit for bit.
    EXPECT_EQ(eval_texture_ref_filtered(table, ref, uv, 0.0f)[0], eval_texture(table[0], moved)[0]);
}

}  // namespace
}  // namespace sombra
