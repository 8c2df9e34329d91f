#include "render/sampler.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "render/chi2_test_util.h"

namespace sombra {
namespace {

// The p-value of χ² for counts that should all be equal.
double uniform_p_value(const std::vector<double>& observed) {
    double total = 0;
    for (double o : observed) total += o;
    return chi2::pearson(observed, std::vector<double>(observed.size(), total / static_cast<double>(observed.size())))
        .p_value;
}

// Whether `points` (in [0, 1)², 2^k of them) put exactly one point in every
// elementary interval [a/2^i, (a+1)/2^i) × [b/2^(k−i), (b+1)/2^(k−i)) of
// area 2^−k, for the split i = `split` of k.
bool one_per_interval(const std::vector<std::pair<float, float>>& points, int k, int split) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> cells;
    for (const auto& [x, y] : points)
        cells.insert({static_cast<std::uint32_t>(x * static_cast<float>(1u << split)),
                      static_cast<std::uint32_t>(y * static_cast<float>(1u << (k - split)))});
    return cells.size() == (std::size_t{1} << k);
}

// A (0, k, 2)-net: one point per elementary interval for every split.
bool is_0k2_net(const std::vector<std::pair<float, float>>& points, int k) {
    for (int split = 0; split <= k; ++split)
        if (!one_per_interval(points, k, split)) return false;
    return true;
}

TEST(Sobol, DirectionNumbersFollowTheRecurrence) {
    // m_i = v_i · 2^i: van der Corput's are all 1; the others from the
    // recurrence by hand, e.g. x + 1: m_i = 2m_{i−1} ⊕ m_{i−1} = 3, 5, 15, 17.
    const std::array<std::array<std::uint32_t, 5>, 4> m = {{
        {1, 1, 1, 1, 1},
        {1, 3, 5, 15, 17},
        {1, 3, 3, 9, 29},
        {1, 3, 1, 5, 31},
    }};
    for (int d = 0; d < 4; ++d)
        for (int i = 0; i < 5; ++i) EXPECT_EQ(sobol::kDirections.v[d][i] >> (31 - i), m[d][i]) << d << " " << i;
    // Every v_i has its lowest set bit at 2^−i (m_i odd and < 2^i+1), so each
    // dimension's matrix is invertible.
    for (int d = 0; d < 4; ++d)
        for (int i = 0; i < 32; ++i) EXPECT_EQ(sobol::kDirections.v[d][i] & (0xffffffffu >> i), 1u << (31 - i));
}

TEST(Sobol, KnownFirstPoints) {
    // Joe and Kuo's listing of the first points (in Gray-code order, as their
    // generator produces them) for the first three dimensions.
    const float expected[7][3] = {{0.5f, 0.5f, 0.5f},       {0.75f, 0.25f, 0.25f},    {0.25f, 0.75f, 0.75f},
                                  {0.375f, 0.375f, 0.625f}, {0.875f, 0.875f, 0.125f}, {0.625f, 0.125f, 0.875f},
                                  {0.125f, 0.625f, 0.375f}};
    for (std::uint32_t n = 1; n <= 7; ++n)
        for (int d = 0; d < 3; ++d)
            EXPECT_EQ(sobol::to_unit(sobol::sample(n ^ (n >> 1), d)), expected[n - 1][d]) << n << " " << d;
    for (int d = 0; d < 4; ++d) EXPECT_EQ(sobol::sample(0, d), 0u);
}

TEST(Sobol, ReversedTablesComputeTheMatrixProduct) {
    for (std::uint32_t k = 0; k < 2000; ++k) {
        const std::uint32_t r = k < 1000 ? k : hash32(k);
        for (int d = 0; d < 4; ++d)
            ASSERT_EQ(sobol::sample_reversed(r, d), sobol::reverse_bits(sobol::sample(sobol::reverse_bits(r), d)))
                << r << " " << d;
        ASSERT_EQ(sobol::sample(r, 0), sobol::reverse_bits(r));
        ASSERT_EQ(sobol::reverse_bits(sobol::reverse_bits(r)), r);
    }
    EXPECT_EQ(sobol::reverse_bits(1u), 0x80000000u);
    EXPECT_EQ(sobol::reverse_bits(0x12345678u), 0x1e6a2c48u);
}

TEST(Sobol, GroupValuesAreScrambledSobolPoints) {
    // value(index, d) = owen_scramble(sample(owen_scramble(index, index seed), d), dimension seed).
    const sobol::Group g{0x1234567u, 0x89abcdefu};
    for (std::uint32_t index = 0; index < 300; ++index)
        for (int d = 0; d < 4; ++d) {
            const std::uint32_t seed = hash32(g.value_seed + static_cast<std::uint32_t>(d) * 0x9e3779b9u);
            const std::uint32_t expected =
                sobol::owen_scramble(sobol::sample(sobol::owen_scramble(index, g.index_seed), d), seed);
            ASSERT_EQ(g.value(index, d), sobol::to_unit(expected)) << index << " " << d;
        }
}

TEST(Sobol, OwenScrambleKeepsAlignedBlocks) {
    // A bijection on 32 bits that maps the aligned block of 2^k holding x
    // onto one aligned block of 2^k: the high 32 − k bits of the result
    // depend only on x's high bits.
    for (std::uint32_t seed : {0u, 1u, 0x9e3779b9u, 0xdeadbeefu})
        for (int k : {1, 4, 10}) {
            std::set<std::uint32_t> images, blocks;
            const std::uint32_t base = 0x5a5a5a5au & ~((1u << k) - 1);
            for (std::uint32_t i = 0; i < (1u << k); ++i) {
                const std::uint32_t y = sobol::owen_scramble(base + i, seed);
                images.insert(y);
                blocks.insert(y >> k);
            }
            EXPECT_EQ(images.size(), std::size_t{1} << k);
            EXPECT_EQ(blocks.size(), 1u);
        }
}

TEST(Sampler, OneSampleIsThePixelCentre) {
    const PixelSample s = pixel_sample(0, 1, pixel_key(7, 3, 4, 10));
    EXPECT_EQ(s.x, 0.5f);
    EXPECT_EQ(s.y, 0.5f);
}

TEST(Sampler, FirstPowerOfTwoSamplesOfAPixelAreA0k2Net) {
    // For every k = 0 … 10, the first 2^k pixel positions put exactly one
    // sample in every elementary interval of area 2^−k, in many pixels.
    for (int p = 0; p < 50; ++p) {
        const std::uint64_t key = pixel_key(42, p, 9, 640);
        std::vector<std::pair<float, float>> points;
        for (std::uint32_t n = 0; n < 1024; ++n) {
            const PixelSample s = pixel_sample(n, 1024, key);
            ASSERT_GE(s.x, 0.0f);
            ASSERT_LT(s.x, 1.0f);
            ASSERT_GE(s.y, 0.0f);
            ASSERT_LT(s.y, 1.0f);
            points.push_back({s.x, s.y});
            const int k = std::countr_zero(n + 1);
            if (((n + 1) & n) == 0) {
                EXPECT_TRUE(is_0k2_net(points, k)) << "pixel " << p << ", first 2^" << k;
            }
        }
    }
}

TEST(Sampler, EveryPrefixIsStratified) {
    // Good for every n, not only powers of two: with 2^a ≤ n < 2^(a+1), the
    // first n samples lie in the aligned block of 2^(a+1) (a (0, a+1, 2)-net)
    // and hold its first 2^a (a (0, a, 2)-net), so every elementary interval
    // of area 2^−a holds one or two of them, for every split.
    for (int p = 0; p < 8; ++p) {
        const std::uint64_t key = pixel_key(77, p, 1, 8);
        std::vector<std::pair<float, float>> points;
        for (std::uint32_t n = 1; n <= 300; ++n) {
            const PixelSample s = pixel_sample(n - 1, 300, key);
            points.push_back({s.x, s.y});
            const int a = std::bit_width(n) - 1;
            for (int split = 0; split <= a; ++split) {
                std::map<std::pair<std::uint32_t, std::uint32_t>, int> cells;
                for (const auto& [x, y] : points)
                    ++cells[{static_cast<std::uint32_t>(x * static_cast<float>(1u << split)),
                             static_cast<std::uint32_t>(y * static_cast<float>(1u << (a - split)))}];
                ASSERT_EQ(cells.size(), std::size_t{1} << a) << "pixel " << p << ", n " << n << ", split " << split;
                for (const auto& [cell, count] : cells) ASSERT_LE(count, 2) << "pixel " << p << ", n " << n;
            }
        }
    }
}

TEST(Sampler, SamplesDoNotDependOnTheCount) {
    // Progressive (spec §18): from 2 spp on, sample n is the same whatever
    // spp ≥ n + 1 the pixel takes, position and every draw.
    const std::uint64_t key = pixel_key(3, 17, 5, 64);
    for (std::uint32_t n = 0; n < 4; ++n) {
        const PixelSample a = pixel_sample(n, 4, key);
        for (std::uint32_t count : {2u, 16u, 256u, 4096u}) {
            if (n >= count) continue;
            const PixelSample b = pixel_sample(n, count, key);
            EXPECT_EQ(a.x, b.x);
            EXPECT_EQ(a.y, b.y);
            SampleStream s1{key, n, 4}, s2{key, n, count};
            EXPECT_EQ(s1.lens_2d().u1, s2.lens_2d().u1);
            for (int draw = 0; draw < 40; ++draw) {
                if (draw % 3 == 1) {
                    const SampleStream::Pair p1 = s1.next_2d(), p2 = s2.next_2d();
                    EXPECT_EQ(p1.u1, p2.u1);
                    EXPECT_EQ(p1.u2, p2.u2);
                } else {
                    EXPECT_EQ(s1.next_1d(), s2.next_1d());
                }
            }
        }
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

TEST(Sampler, PositionsAreUniformAcrossPixels) {
    // One sample index per pixel, over many pixels: independent uniform
    // points (χ² on 16 bins per axis and on an 8×8 grid), for the first
    // sample and a later one.
    for (std::uint32_t n : {0u, 5u, 100u}) {
        std::vector<double> xs(16, 0.0), ys(16, 0.0), grid(64, 0.0);
        for (int p = 0; p < 20000; ++p) {
            const PixelSample s = pixel_sample(n, 128, pixel_key(5, p % 200, p / 200, 200));
            ++xs[static_cast<int>(s.x * 16)];
            ++ys[static_cast<int>(s.y * 16)];
            ++grid[static_cast<int>(s.x * 8) * 8 + static_cast<int>(s.y * 8)];
        }
        EXPECT_GT(uniform_p_value(xs), 1e-3) << n;
        EXPECT_GT(uniform_p_value(ys), 1e-3) << n;
        EXPECT_GT(uniform_p_value(grid), 1e-3) << n;
    }
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

// The path integrator's draws at one vertex: 1-D, 2-D, 1-D, 2-D, 1-D.
struct VertexDraws {
    float choice;
    SampleStream::Pair light;
    float lobe;
    SampleStream::Pair bsdf;
    float roulette;
};

// The path integrator's draws at one vertex, in its order: each 1-D choice
// right after the 2-D draw it goes with, so that it takes dimension 2 of the
// same group (see ChoicesAndTheirPointsAreStratifiedTogether).
VertexDraws draw_vertex(SampleStream& s) {
    VertexDraws v{};
    v.light = s.next_2d();
    v.choice = s.next_1d();
    v.bsdf = s.next_2d();
    v.lobe = s.next_1d();
    v.roulette = s.next_1d();
    return v;
}

// Whether every elementary interval of area 2^(t−k) (each split) holds
// exactly 2^t of the 2^k `points`: a (t, k, 2)-net.
bool is_tk2_net(const std::vector<std::pair<float, float>>& points, int t, int k) {
    for (int split = 0; split <= k - t; ++split) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> cells;
        for (const auto& [x, y] : points)
            ++cells[{static_cast<std::uint32_t>(x * static_cast<float>(1u << split)),
                     static_cast<std::uint32_t>(y * static_cast<float>(1u << (k - t - split)))}];
        if (cells.size() != (std::size_t{1} << (k - t))) return false;
        for (const auto& [cell, count] : cells)
            if (count != (1 << t)) return false;
    }
    return true;
}

TEST(SampleStream, EveryDrawOfThePowerOfTwoPrefixIsStratified) {
    // For the first 2^k samples of a pixel (k = 0 … 8), at the first three
    // path vertices: every 2-D draw is a (0, k, 2)-net, and every 1-D draw
    // holds one value in each 1/2^k stratum.
    for (int p = 0; p < 10; ++p) {
        const std::uint64_t key = pixel_key(11, p, 3, 32);
        for (int k = 0; k <= 8; ++k) {
            const std::uint32_t n = 1u << k;
            std::vector<std::vector<std::pair<float, float>>> pairs(6);
            std::vector<std::set<std::uint32_t>> strata(9);
            for (std::uint32_t i = 0; i < n; ++i) {
                SampleStream s{key, i, 256};
                for (int vertex = 0; vertex < 3; ++vertex) {
                    const VertexDraws v = draw_vertex(s);
                    pairs[2 * vertex].push_back({v.light.u1, v.light.u2});
                    pairs[2 * vertex + 1].push_back({v.bsdf.u1, v.bsdf.u2});
                    for (int d = 0; d < 3; ++d) {
                        const float u = d == 0 ? v.choice : d == 1 ? v.lobe : v.roulette;
                        ASSERT_GE(u, 0.0f);
                        ASSERT_LT(u, 1.0f);
                        strata[3 * vertex + d].insert(static_cast<std::uint32_t>(u * static_cast<float>(n)));
                    }
                }
            }
            for (std::size_t d = 0; d < pairs.size(); ++d)
                EXPECT_TRUE(is_0k2_net(pairs[d], k)) << "pixel " << p << ", 2-D draw " << d << ", 2^" << k;
            for (std::size_t d = 0; d < strata.size(); ++d)
                EXPECT_EQ(strata[d].size(), n) << "pixel " << p << ", 1-D draw " << d << ", 2^" << k;
        }
    }
}

TEST(SampleStream, DimensionsTwoAndThreeAreStratifiedOnlyIn1D) {
    // Why 2-D draws take a group's dimensions (0, 1) only. Measured over
    // k = 0 … 10 (a Python model of the same recurrence agrees): the pair
    // (2, 3) of x² + x + 1 and x³ + x + 1 is a (0, k, 2)-net for k = 0, 1, 4
    // only; for the other k some split of the elementary intervals holds
    // two points in one, e.g. k = 3 fails both 2×4 and 4×2, while the 1-D
    // splits (2^k × 1 and 1 × 2^k) always hold one point each.
    const sobol::Group g = sample_group(pixel_key(2, 7, 7, 16), 3);
    for (int k = 0; k <= 10; ++k) {
        std::vector<std::pair<float, float>> points;
        for (std::uint32_t i = 0; i < (1u << k); ++i) points.push_back({g.value(i, 2), g.value(i, 3)});
        EXPECT_TRUE(one_per_interval(points, k, 0)) << k;
        EXPECT_TRUE(one_per_interval(points, k, k)) << k;
        EXPECT_EQ(is_0k2_net(points, k), k <= 1 || k == 4) << k;
    }
}

TEST(SampleStream, DrawsAreUniformAcrossPixels) {
    // One sample index per pixel over many pixels: every draw of the first
    // two vertices is uniform (χ² on 16 bins, 8×8 cells for pairs).
    for (std::uint32_t n : {0u, 3u, 77u}) {
        std::vector<std::vector<double>> bins(6, std::vector<double>(16, 0.0));
        std::vector<std::vector<double>> cells(4, std::vector<double>(64, 0.0));
        for (int p = 0; p < 16000; ++p) {
            SampleStream s{pixel_key(13, p, 1, 1 << 20), n, 128};
            for (int vertex = 0; vertex < 2; ++vertex) {
                const VertexDraws v = draw_vertex(s);
                ++bins[3 * vertex][static_cast<int>(v.choice * 16)];
                ++bins[3 * vertex + 1][static_cast<int>(v.lobe * 16)];
                ++bins[3 * vertex + 2][static_cast<int>(v.roulette * 16)];
                ++cells[2 * vertex][static_cast<int>(v.light.u1 * 8) * 8 + static_cast<int>(v.light.u2 * 8)];
                ++cells[2 * vertex + 1][static_cast<int>(v.bsdf.u1 * 8) * 8 + static_cast<int>(v.bsdf.u2 * 8)];
            }
        }
        for (std::size_t d = 0; d < bins.size(); ++d) EXPECT_GT(uniform_p_value(bins[d]), 1e-3) << n << " 1-D " << d;
        for (std::size_t d = 0; d < cells.size(); ++d) EXPECT_GT(uniform_p_value(cells[d]), 1e-3) << n << " 2-D " << d;
    }
}

TEST(SampleStream, GroupsDoNotCorrelate) {
    // All 256 samples of each of 64 pixels: pairs of the same sample's
    // values from different groups (the pixel position and the first
    // vertex's light and BSDF pairs, the lens) fill an 8×8 grid as
    // independent uniforms would; groups sharing their index shuffle or
    // scrambles would pile up on a diagonal or a lattice. Each value alone
    // is stratified per pixel, so each row and column sum is exact and χ²
    // tests only the dependence.
    const int pairs = 5;
    std::vector<std::vector<double>> grids(pairs, std::vector<double>(64, 0.0));
    auto cell = [](float a, float b) { return static_cast<int>(a * 8) * 8 + static_cast<int>(b * 8); };
    for (int p = 0; p < 64; ++p) {
        const std::uint64_t key = pixel_key(21, p, 0, 64);
        for (std::uint32_t i = 0; i < 256; ++i) {
            const PixelSample pos = pixel_sample(i, 256, key);
            SampleStream s{key, i, 256};
            const SampleStream::Pair lens = s.lens_2d();
            const VertexDraws v0 = draw_vertex(s);
            const VertexDraws v1 = draw_vertex(s);
            ++grids[0][cell(pos.x, v0.light.u1)];
            ++grids[1][cell(v0.light.u1, v0.bsdf.u1)];
            ++grids[2][cell(v0.bsdf.u2, v1.light.u2)];
            ++grids[3][cell(pos.y, lens.u2)];
            ++grids[4][cell(v0.lobe, v1.lobe)];  // dimension 2 of groups 1 and 3
        }
    }
    for (int d = 0; d < pairs; ++d) EXPECT_GT(uniform_p_value(grids[d]), 1e-3) << "pair " << d;
}

TEST(SampleStream, OneSampleDrawsAreIndependentHashes) {
    // At 1 spp the draws are version 1's: hash_to_unit of the sample index
    // under a key per dimension (so 1-spp images stay bit for bit).
    const std::uint64_t key = pixel_key(4, 2, 1, 8);
    SampleStream s{key, 0, 1};
    for (std::uint64_t d = 1; d <= 3; ++d)
        EXPECT_EQ(s.next_1d(), hash_to_unit(0, mix64(key ^ (d * 0x9e3779b97f4a7c15ull))));
}

TEST(SampleStream, DimensionsDoNotCorrelateAtOneSample) {
    const int cells = 8;
    std::vector<double> grid(cells * cells, 0.0);
    for (int pixel = 0; pixel < 4000; ++pixel) {
        SampleStream stream{pixel_key(9, pixel, 0, 100000), 0, 1};
        const float a = stream.next_1d();
        const float b = stream.next_1d();
        const SampleStream::Pair c = stream.next_2d();
        ++grid[static_cast<int>(a * cells) * cells + static_cast<int>(b * cells)];
        ++grid[static_cast<int>(c.u1 * cells) * cells + static_cast<int>(a * cells)];
    }
    EXPECT_GT(uniform_p_value(grid), 1e-3);
}

TEST(SampleStream, DeterministicAndDifferentPerSample) {
    SampleStream a{pixel_key(1, 2, 3, 10), 5, 16};
    SampleStream b{pixel_key(1, 2, 3, 10), 5, 16};
    SampleStream c{pixel_key(1, 2, 3, 10), 6, 16};
    const float a1 = a.next_1d(), b1 = b.next_1d(), c1 = c.next_1d();
    EXPECT_EQ(a1, b1);
    EXPECT_NE(a1, c1);
}

TEST(SampleStream, ReadingATakenSlotGivesWhatTheDrawWouldHave) {
    // A vertex takes five slots and reads some of them, in any order, or
    // none: every value read, and every later draw, is what drawing them
    // all in order gives. Both modes: progressive and one sample.
    for (const std::uint32_t count : {1u, 64u}) {
        for (std::uint32_t i = 0; i < 16; ++i) {
            SampleStream drawn{pixel_key(3, 4, 5, 16), i, count};
            SampleStream taken{pixel_key(3, 4, 5, 16), i, count};
            for (int vertex = 0; vertex < 4; ++vertex) {
                const SampleStream::Pair light = drawn.next_2d();
                const float choice = drawn.next_1d();
                const SampleStream::Pair bsdf = drawn.next_2d();
                const float lobe = drawn.next_1d();
                const float roulette = drawn.next_1d();
                const SampleStream::Slot light_slot = taken.take_2d(), choice_slot = taken.take_1d(),
                                         bsdf_slot = taken.take_2d(), lobe_slot = taken.take_1d(),
                                         roulette_slot = taken.take_1d();
                if (vertex % 2 == 0) {  // read backwards, the light's slots last
                    EXPECT_EQ(taken.read_1d(roulette_slot), roulette);
                    EXPECT_EQ(taken.read_1d(lobe_slot), lobe);
                    const SampleStream::Pair b = taken.read_2d(bsdf_slot);
                    EXPECT_EQ(b.u1, bsdf.u1);
                    EXPECT_EQ(b.u2, bsdf.u2);
                    EXPECT_EQ(taken.read_1d(choice_slot), choice);
                    const SampleStream::Pair l = taken.read_2d(light_slot);
                    EXPECT_EQ(l.u1, light.u1);
                    EXPECT_EQ(l.u2, light.u2);
                }  // odd vertices read nothing
            }
            EXPECT_EQ(taken.next_1d(), drawn.next_1d()) << count << " spp, sample " << i;
        }
    }
}

TEST(SampleStream, ChoicesAndTheirPointsAreStratifiedTogether) {
    // A vertex chooses an emitter (or a BSDF lobe) with a 1-D draw, then
    // samples it with a 2-D draw. Drawn right after the 2-D draw, the choice
    // is dimension 2 of the same group, so the points whose choice falls in
    // one half are themselves a (1, k − 1, 2)-net: every elementary interval
    // of area 2^(2−k) holds two of them. Drawn before it (the order before
    // 2026-11-27) the halves are random subsets of the net: from k = 5 on,
    // not even a (2, k − 1, 2)-net. On the spheres scene's direct light that
    // order had 26 % more error (docs/performance.md).
    for (int p = 0; p < 20; ++p) {
        for (int k = 2; k <= 10; ++k) {
            std::vector<std::pair<float, float>> halves[2][2];  // [draw: light, bsdf][choice < 1/2]
            std::vector<std::pair<float, float>> before[2];     // the light draw with the choice drawn first
            for (std::uint32_t i = 0; i < (1u << k); ++i) {
                SampleStream s{pixel_key(5, p, 1, 32), i, 1024};
                const VertexDraws v = draw_vertex(s);
                halves[0][v.choice < 0.5f ? 1 : 0].push_back({v.light.u1, v.light.u2});
                halves[1][v.lobe < 0.5f ? 1 : 0].push_back({v.bsdf.u1, v.bsdf.u2});
                SampleStream old{pixel_key(5, p, 1, 32), i, 1024};
                const float choice = old.next_1d();
                const SampleStream::Pair light = old.next_2d();
                before[choice < 0.5f ? 1 : 0].push_back({light.u1, light.u2});
            }
            for (int draw = 0; draw < 2; ++draw)
                for (const auto& half : halves[draw]) {
                    ASSERT_EQ(half.size(), std::size_t{1} << (k - 1)) << "pixel " << p << ", 2^" << k;
                    EXPECT_TRUE(is_tk2_net(half, 1, k - 1)) << "pixel " << p << ", draw " << draw << ", 2^" << k;
                }
            if (k >= 5) {
                EXPECT_FALSE(is_tk2_net(before[0], 2, k - 1) && is_tk2_net(before[1], 2, k - 1)) << k;
            }
        }
    }
}

}  // namespace
}  // namespace sombra
