// Where in a pixel each sample goes, and the random numbers each sample's
// path draws. Every value is a pure function of (seed, pixel, sample index,
// dimension), never of thread or order, so images are the same for any
// thread count.
#pragma once

#include <cmath>
#include <cstdint>

namespace sombra {

// SplitMix64's finaliser: a well-mixed 64-bit hash (Steele et al. 2014).
constexpr std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// A uniform float in [0, 1) from a hash of (index, key).
inline float hash_to_unit(std::uint32_t index, std::uint64_t key) {
    const std::uint64_t h = mix64(key ^ (static_cast<std::uint64_t>(index) * 0xd1b54a32d192ed03ull));
    return static_cast<float>(h >> 40) * 0x1p-24f;  // 24 bits: exactly representable, < 1
}

// A pseudo-random permutation of [0, n): a bijective hash on the smallest
// power-of-two range holding n, applied until the value falls inside
// ("cycle walking"), as in Kensler's correlated multi-jittered sampling.
// Kept for pixel positions only, so that version-1 images stay bit for bit
// as they were; its permutations of small n are few (see shuffle_index).
inline std::uint32_t permute_index(std::uint32_t i, std::uint32_t n, std::uint32_t key) {
    std::uint32_t mask = n - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    do {
        // Each step is a bijection on [0, mask]: xor, odd multiply, xorshift.
        i ^= key & mask;
        i = (i * 0x9e3779b1u) & mask;
        i ^= (i & mask) >> 7;
        i = (i * 0x85ebca6bu + (key >> 16)) & mask;
        i ^= (i & mask) >> 11;
        i = (i * 0xc2b2ae35u) & mask;
        i ^= (i & mask) >> 5;
    } while (i >= n);
    return i;
}

struct PixelSample {
    float x, y;  // offset inside the pixel, each in [0, 1)
};

// Sample `index` of `count` for the pixel keyed by `pixel_key`: with one
// sample, the pixel centre (spec §3); otherwise correlated multi-jittered
// sampling (Kensler 2013), stratified in both 1-D projections and in an
// m×n grid of cells, for any count.
inline PixelSample pixel_sample(std::uint32_t index, std::uint32_t count, std::uint64_t pixel_key) {
    if (count <= 1) return {0.5f, 0.5f};
    const auto m = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(count)));
    const std::uint32_t n = (count + m - 1) / m;
    const auto key = static_cast<std::uint32_t>(pixel_key);
    const std::uint32_t s = permute_index(index, count, key * 0x51633e2du);
    const std::uint32_t sx = permute_index(s % m, m, key * 0x68bc21ebu);
    const std::uint32_t sy = permute_index(s / m, n, key * 0x02e5be93u);
    const float jx = hash_to_unit(s, pixel_key ^ 0x967a889b00000000ull);
    const float jy = hash_to_unit(s, pixel_key ^ 0x368cc8b700000000ull);
    const float x = (static_cast<float>(sx) + (static_cast<float>(sy) + jx) / static_cast<float>(n)) / static_cast<float>(m);
    const float y = (static_cast<float>(s) + jy) / static_cast<float>(count);
    // Float rounding can reach 1.0 exactly; stay inside the pixel.
    return {x < 1.0f ? x : 0x1.fffffep-1f, y < 1.0f ? y : 0x1.fffffep-1f};
}

// A 32-bit integer hash with good avalanche (Wellons' "lowbias32").
constexpr std::uint32_t hash32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// A pseudo-random permutation of [0, n) chosen by `key`: a ten-round
// Feistel network (Luby–Rackoff) with hash32 as round function, on the
// smallest even number of bits (at least 2) that holds n, cycle-walked into
// [0, n). Unlike permute_index, whose few fixed operations yield only 8
// distinct permutations of 4 elements, its permutations of small n are
// close to uniformly distributed (fewer rounds are measurably not: see
// sampler_test.cpp), so dimensions shuffled with different keys do not
// correlate.
inline std::uint32_t shuffle_index(std::uint32_t i, std::uint32_t n, std::uint64_t key) {
    int bits = 2;
    while (bits < 32 && (std::uint64_t{1} << bits) < n) bits += 2;
    const int half = bits / 2;
    const std::uint32_t half_mask = (std::uint32_t{1} << half) - 1;
    const std::uint64_t k = mix64(key);
    const auto k0 = static_cast<std::uint32_t>(k), k1 = static_cast<std::uint32_t>(k >> 32) | 1u;
    do {
        std::uint32_t left = i >> half, right = i & half_mask;
        for (std::uint32_t round = 0; round < 10; ++round) {
            const std::uint32_t next = left ^ (hash32(right ^ (k0 + round * k1)) & half_mask);
            left = right;
            right = next;
        }
        i = (left << half) | right;
    } while (i >= n);
    return i;
}

// The random numbers of one sample (pixel, sample index) beyond its position
// in the pixel: each call draws a new dimension. The first
// kStratifiedDimensions draws (a path's first vertex: light choice, light
// point, BSDF lobe, BSDF direction, roulette) are stratified over the
// pixel's `count` samples: in 1-D one value per 1/count stratum, in 2-D one
// per cell of a jittered m×n grid, the strata visited in an order shuffled
// with an independent key per dimension, so that dimensions do not
// correlate. Later draws, where stratification no longer pays for its cost,
// and every draw when count = 1, are independent uniform hashes.
struct SampleStream {
    static constexpr std::uint32_t kStratifiedDimensions = 5;

    std::uint64_t pixel_key = 0;
    std::uint32_t index = 0;  // this sample's index among the pixel's
    std::uint32_t count = 1;  // the pixel's samples
    std::uint32_t dimension = 0;

    float next_1d() {
        const bool stratified = count > 1 && dimension < kStratifiedDimensions;
        const std::uint64_t key = dimension_key();
        if (!stratified) return hash_to_unit(index, key);
        const std::uint32_t s = shuffle_index(index, count, key);
        return to_unit((static_cast<float>(s) + hash_to_unit(s, key ^ 0x5bd1e995ull)) / static_cast<float>(count));
    }

    struct Pair {
        float u1, u2;
    };
    Pair next_2d() {
        const bool stratified = count > 1 && dimension < kStratifiedDimensions;
        return pair(dimension_key(), stratified);
    }

    // The thin lens's point (spec §17): a stratified 2-D dimension of its
    // own, keyed apart from the sequence next_1d and next_2d walk, so that
    // opening the aperture leaves every other draw of the sample as it was.
    Pair lens_2d() const { return pair(mix64(pixel_key ^ 0x6c656e73ull * 0x9e3779b97f4a7c15ull), count > 1); }

private:
    Pair pair(std::uint64_t key, bool stratified) const {
        if (!stratified) return {hash_to_unit(index, key), hash_to_unit(index, key ^ 0x368cc8b700000000ull)};
        const auto m = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(count)));
        const std::uint32_t n = (count + m - 1) / m;
        const std::uint32_t s = shuffle_index(index, count, key);
        const float jx = hash_to_unit(s, key ^ 0x967a889b00000000ull);
        const float jy = hash_to_unit(s, key ^ 0x368cc8b700000000ull);
        const std::uint32_t column = s % m, row = s / m;  // s's cell in the grid of n rows of m
        return {to_unit((static_cast<float>(column) + jx) / static_cast<float>(m)),
                to_unit((static_cast<float>(row) + jy) / static_cast<float>(n))};
    }

    std::uint64_t dimension_key() {
        ++dimension;
        return mix64(pixel_key ^ (static_cast<std::uint64_t>(dimension) * 0x9e3779b97f4a7c15ull));
    }
    // Float rounding can reach 1.0 exactly; stay below it.
    static float to_unit(float x) { return x < 1.0f ? x : 0x1.fffffep-1f; }
};

// The key that seeds pixel (i, j)'s samples for a render seed.
inline std::uint64_t pixel_key(std::uint64_t seed, int i, int j, int width) {
    return mix64(mix64(seed) ^ (static_cast<std::uint64_t>(j) * static_cast<std::uint64_t>(width) + static_cast<std::uint64_t>(i)));
}

}  // namespace sombra
