#include "render/sampler.h"

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <set>
#include <vector>

#include "render/chi2_test_util.h"

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

namespace sombra {
namespace {

// The p-value of χ² for counts that should all be equal.
double uniform_p_value(const std::vector<double>& observed) {
    double total = 0;
    for (double o : observed) total += o;
    return chi2::pearson(observed, std::vector<double>(observed.size(), total / static_cast<double>(observed.size()))).p_value;
}

TEST(SampleStream, ShuffleIndexIsAPermutation) {
    for (std::uint32_t n : {1u, 2u, 3u, 4u, 7u, 16u, 17u, 100u, 1000u, 65536u}) {
        for (std::uint64_t key : {0ull, 1ull, 0xdeadbeefcafeull}) {
            std::vector<bool> seen(n, false);
            for (std::uint32_t i = 0; i < n; ++i) {
                const std::uint32_t p = shuffle_index(i, n, key);
                ASSERT_LT(p, n);
                EXPECT_FALSE(seen[p]);
                seen[p] = true;
            }
        }
    }
}

TEST(SampleStream, ShufflesOfFourAreUniformOverAll24Permutations) {
    // The old permute_index reaches only 8 of the 24; a proper keyed
    // permutation reaches all, each about equally often (χ² test).
    std::map<std::array<std::uint32_t, 4>, int> counts;
    const int keys = 24000;
    for (int k = 0; k < keys; ++k) {
        std::array<std::uint32_t, 4> perm{};
        for (std::uint32_t i = 0; i < 4; ++i) perm[i] = shuffle_index(i, 4, mix64(static_cast<std::uint64_t>(k)));
        ++counts[perm];
    }
    ASSERT_EQ(counts.size(), 24u);
    std::vector<double> observed;
    for (const auto& [perm, c] : counts) observed.push_back(c);
    EXPECT_GT(uniform_p_value(observed), 1e-3);
}

TEST(SampleStream, FirstDimensionsAreStratifiedOverThePixelsSamples) {
    // The path integrator's first vertex draws 1-D, 2-D, 1-D, 2-D, 1-D.
    for (std::uint32_t count : {4u, 7u, 16u, 64u}) {
        const auto m = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(count)));
        const std::uint32_t n = (count + m - 1) / m;
        std::vector<std::set<std::uint32_t>> strata1(3), cells(2);
        for (std::uint32_t k = 0; k < count; ++k) {
            SampleStream stream{pixel_key(3, 1, 2, 10), k, count};
            for (int d = 0; d < 3; ++d) {
                const float u = stream.next_1d();
                ASSERT_GE(u, 0.0f);
                ASSERT_LT(u, 1.0f);
                strata1[d].insert(static_cast<std::uint32_t>(u * static_cast<float>(count)));
                if (d == 2) break;
                const SampleStream::Pair p = stream.next_2d();
                ASSERT_LT(p.u1, 1.0f);
                ASSERT_LT(p.u2, 1.0f);
                const auto cx = static_cast<std::uint32_t>(p.u1 * static_cast<float>(m));
                const auto cy = static_cast<std::uint32_t>(p.u2 * static_cast<float>(n));
                cells[d].insert(cy * m + cx);
            }
        }
        for (int d = 0; d < 3; ++d) EXPECT_EQ(strata1[d].size(), count) << "1-D draw " << d;
        for (int d = 0; d < 2; ++d) EXPECT_EQ(cells[d].size(), count) << "2-D draw " << d;
    }
}

TEST(SampleStream, DimensionsDoNotCorrelate) {
    // Pairs (dimension a, dimension b) of the same sample, over many pixels
    // and samples, fill an 8×8 grid uniformly; correlated dimensions (the
    // same permutation for both) would pile up on the diagonal.
    const int cells = 8;
    for (std::uint32_t count : {1u, 4u, 16u}) {
        std::vector<double> grid(cells * cells, 0.0);
        for (int pixel = 0; pixel < 4000 / static_cast<int>(count) + 1; ++pixel)
            for (std::uint32_t k = 0; k < count; ++k) {
                SampleStream stream{pixel_key(9, pixel, 0, 100000), k, count};
                const float a = stream.next_1d();
                const float b = stream.next_1d();
                const SampleStream::Pair c = stream.next_2d();
                ++grid[static_cast<int>(a * cells) * cells + static_cast<int>(b * cells)];
                ++grid[static_cast<int>(c.u1 * cells) * cells + static_cast<int>(a * cells)];
            }
        EXPECT_GT(uniform_p_value(grid), 1e-3) << "count " << count;
    }
}

TEST(SampleStream, DeterministicAndDifferentPerSample) {
    SampleStream a{pixel_key(1, 2, 3, 10), 5, 16};
    SampleStream b{pixel_key(1, 2, 3, 10), 5, 16};
    SampleStream c{pixel_key(1, 2, 3, 10), 6, 16};
    const float a1 = a.next_1d(), b1 = b.next_1d(), c1 = c.next_1d();
    EXPECT_EQ(a1, b1);
    EXPECT_NE(a1, c1);
}

}  // namespace
}  // namespace sombra
