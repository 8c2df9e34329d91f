#include "render/sampler.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace sombra {
namespace {

TEST(Sampler, OneSampleIsThePixelCentre) {
    const PixelSample s = pixel_sample(0, 1, pixel_key(7, 3, 4, 10));
    EXPECT_EQ(s.x, 0.5f);
    EXPECT_EQ(s.y, 0.5f);
}

TEST(Sampler, PermuteIndexIsAPermutation) {
    for (std::uint32_t n : {1u, 2u, 3u, 7u, 16u, 17u, 100u, 1000u}) {
        for (std::uint32_t key : {0u, 1u, 0xdeadbeefu}) {
            std::set<std::uint32_t> seen;
            for (std::uint32_t i = 0; i < n; ++i) {
                const std::uint32_t p = permute_index(i, n, key);
                EXPECT_LT(p, n);
                seen.insert(p);
            }
            EXPECT_EQ(seen.size(), n) << "n=" << n << " key=" << key;
        }
    }
}

TEST(Sampler, SamplesAreStratifiedInBothProjections) {
    for (std::uint32_t count : {4u, 9u, 16u, 12u, 7u, 64u}) {
        const std::uint64_t key = pixel_key(42, 5, 9, 640);
        std::set<std::uint32_t> rows;
        std::set<std::uint32_t> cols;
        const auto m = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(count)));
        const std::uint32_t n = (count + m - 1) / m;
        for (std::uint32_t k = 0; k < count; ++k) {
            const PixelSample s = pixel_sample(k, count, key);
            ASSERT_GE(s.x, 0.0f);
            ASSERT_LT(s.x, 1.0f);
            ASSERT_GE(s.y, 0.0f);
            ASSERT_LT(s.y, 1.0f);
            rows.insert(static_cast<std::uint32_t>(s.y * static_cast<float>(count)));
            cols.insert(static_cast<std::uint32_t>(s.x * static_cast<float>(m * n)));
        }
        // One sample in each of the `count` horizontal strips, and no two in
        // the same of the m·n vertical ones.
        EXPECT_EQ(rows.size(), count) << count;
        EXPECT_EQ(cols.size(), count) << count;
    }
}

TEST(Sampler, DeterministicPerPixelAndSeed) {
    const std::uint64_t a = pixel_key(1, 10, 20, 100);
    EXPECT_EQ(a, pixel_key(1, 10, 20, 100));
    EXPECT_NE(a, pixel_key(2, 10, 20, 100));
    EXPECT_NE(a, pixel_key(1, 11, 20, 100));
    const PixelSample s1 = pixel_sample(3, 8, a), s2 = pixel_sample(3, 8, a);
    EXPECT_EQ(s1.x, s2.x);
    EXPECT_EQ(s1.y, s2.y);
    const PixelSample other = pixel_sample(3, 8, pixel_key(1, 11, 20, 100));
    EXPECT_TRUE(other.x != s1.x || other.y != s1.y);
}

TEST(Sampler, AveragesToThePixelCentre) {
    // Over many pixels, the mean sample position is the centre.
    double sx = 0, sy = 0;
    int total = 0;
    for (int p = 0; p < 2000; ++p)
        for (std::uint32_t k = 0; k < 5; ++k) {
            const PixelSample s = pixel_sample(k, 5, pixel_key(0, p, 0, 4096));
            sx += s.x;
            sy += s.y;
            ++total;
        }
    EXPECT_NEAR(sx / total, 0.5, 0.01);
    EXPECT_NEAR(sy / total, 0.5, 0.01);
}

}  // namespace
}  // namespace sombra
