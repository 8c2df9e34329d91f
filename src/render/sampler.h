// Where in a pixel each sample goes, and the random numbers each sample's
// path draws. Every value is a pure function of (seed, pixel, sample index,
// dimension), never of thread or order, so images are the same for any
// thread count.
#pragma once

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

// A 32-bit integer hash with good avalanche (Wellons' "lowbias32").
constexpr std::uint32_t hash32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// 4-D Sobol points (Joe & Kuo 2008). Dimension 0 is the van der Corput
// sequence; dimensions 1–3 come from the primitive polynomials x + 1,
// x² + x + 1 and x³ + x + 1 with Joe–Kuo's initial numbers m = {1}, {1, 3},
// {1, 3, 1}. Dimensions (0, 1) form a (0, 2)-sequence: every aligned block
// of 2^k points is a (0, k, 2)-net.
namespace sobol {

inline constexpr int kDimensions = 4;
inline constexpr int kBits = 32;

struct Directions {
    std::uint32_t v[kDimensions][kBits];  // v[d][b]: what index bit b xors into dimension d, as a 0.32 fraction
};

// The direction numbers from the standard recurrence: for a polynomial of
// degree s with middle coefficients a_1 … a_{s−1},
// m_i = 2a_1·m_{i−1} ⊕ 4a_2·m_{i−2} ⊕ … ⊕ 2^s·m_{i−s} ⊕ m_{i−s}, and
// v_i = m_i / 2^i.
constexpr Directions make_directions() {
    struct Polynomial {
        int degree;
        std::uint32_t middle;  // a_1 … a_{s−1}, a_1 the most significant bit
        std::uint32_t m[3];    // the initial odd numbers m_1 … m_s
    };
    constexpr Polynomial polynomials[kDimensions] = {
        {1, 0, {1, 0, 0}},  // unused: dimension 0 is the identity (m_i = 1)
        {1, 0, {1, 0, 0}},  // x + 1
        {2, 1, {1, 3, 0}},  // x² + x + 1
        {3, 1, {1, 3, 1}},  // x³ + x + 1
    };
    Directions out{};
    for (int d = 0; d < kDimensions; ++d) {
        std::uint64_t m[kBits] = {};
        const Polynomial& p = polynomials[d];
        for (int i = 0; i < kBits; ++i) {
            if (d == 0) {
                m[i] = 1;
            } else if (i < p.degree) {
                m[i] = p.m[i];
            } else {
                const int s = p.degree;
                m[i] = m[i - s] ^ (m[i - s] << s);
                for (int k = 1; k < s; ++k)
                    if ((p.middle >> (s - 1 - k)) & 1u) m[i] ^= m[i - k] << k;
            }
            out.v[d][i] = static_cast<std::uint32_t>(m[i] << (kBits - 1 - i));  // m_i < 2^(i+1)
        }
    }
    return out;
}

inline constexpr Directions kDirections = make_directions();

// Point `index` of the sequence in `dimension` (0 … 3), as a 0.32 fraction:
// the xor of v[dimension][b] over the set bits b of `index`. The
// definition; the renderer computes it reversed, by table (sample_reversed).
constexpr std::uint32_t sample(std::uint32_t index, int dimension) {
    std::uint32_t x = 0;
    for (int b = 0; b < kBits; ++b)
        if ((index >> b) & 1u) x ^= kDirections.v[dimension][b];
    return x;
}

constexpr std::uint32_t reverse_bits(std::uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    return __builtin_bswap32(x);
}

// The matrices with both index and value bit-reversed, by nibble:
// kReversedNibbles.t[d][n][x] is the xor of reverse_bits(v[d][31 − (4n + j)])
// over the set bits j of x (0 … 15), so that sample_reversed costs 8 table
// lookups (2 KiB in all), where the bitwise product would cost 32
// conditional xors on an effectively random index, whose branches
// mispredict.
struct ReversedNibbles {
    std::uint32_t t[kDimensions][kBits / 4][16];
};

constexpr ReversedNibbles make_reversed_nibbles() {
    ReversedNibbles out{};
    for (int d = 0; d < kDimensions; ++d)
        for (int n = 0; n < kBits / 4; ++n)
            for (std::uint32_t x = 0; x < 16; ++x)
                for (int j = 0; j < 4; ++j)
                    if ((x >> j) & 1u) out.t[d][n][x] ^= reverse_bits(kDirections.v[d][kBits - 1 - (4 * n + j)]);
    return out;
}

inline constexpr ReversedNibbles kReversedNibbles = make_reversed_nibbles();

// reverse_bits(sample(reverse_bits(r), dimension)): the point of the
// reversed index r, reversed, which is the form the Owen scramble below
// works on, so that neither reversal is computed.
constexpr std::uint32_t sample_reversed(std::uint32_t r, int dimension) {
    std::uint32_t x = 0;
    for (int n = 0; n < kBits / 4; ++n) x ^= kReversedNibbles.t[dimension][n][(r >> (4 * n)) & 15u];
    return x;
}

// A hash-based nested uniform (Owen) scramble, on the bits reversed (Burley
// 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)): each step,
// adding the seed or xoring in a multiple by an even constant, flips a bit
// only as a function of the bits below it, i.e. (reversed) of the more
// significant digits of the fraction, which is what an Owen scramble does.
// The constants are the paper's Laine–Karras variant.
constexpr std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

// The Owen scramble of a 0.32 fraction chosen by `seed`: a bijection on
// 32-bit values that maps every aligned block of 2^k onto an aligned block
// of 2^k, so it keeps a net a net.
constexpr std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
    return reverse_bits(laine_karras(reverse_bits(x), seed));
}

// A 0.32 fraction as a float in [0, 1): its top 24 bits, exactly.
constexpr float to_unit(std::uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

// One randomised 4-D Sobol sequence: the sample index is Owen-scrambled
// first (its low bits permuted as a function of its high bits: Burley's
// "shuffled" index), so that samples 0 … 2^k − 1 take one aligned block of
// 2^k Sobol points, a (0, k, 2)-net in dimensions (0, 1), whatever the
// block; then each dimension's value is Owen-scrambled with a seed of its
// own.
struct Group {
    std::uint32_t index_seed = 0;
    std::uint32_t value_seed = 0;  // hashed with the dimension into each dimension's seed

    // The shuffled index owen_scramble(index, index_seed), left bit-reversed
    // (sample_reversed takes it so).
    std::uint32_t shuffled_reversed(std::uint32_t index) const { return laine_karras(reverse_bits(index), index_seed); }
    // Dimension `dimension` of the point whose shuffled index, reversed, is
    // `r`: owen_scramble(sample(reverse_bits(r), dimension), seed).
    float value_at(std::uint32_t r, int dimension) const {
        const std::uint32_t seed = hash32(value_seed + static_cast<std::uint32_t>(dimension) * 0x9e3779b9u);
        return to_unit(reverse_bits(laine_karras(sample_reversed(r, dimension), seed)));
    }
    float value(std::uint32_t index, int dimension) const { return value_at(shuffled_reversed(index), dimension); }
};

}  // namespace sobol

// The sequence of group `group` (0, 1, …) of the pixel keyed by
// `pixel_key`: each group's seed independent of every other's.
inline sobol::Group sample_group(std::uint64_t pixel_key, std::uint64_t group) {
    const std::uint64_t h = mix64(pixel_key ^ ((group + 1) * 0xd1b54a32d192ed03ull));
    return {static_cast<std::uint32_t>(h), static_cast<std::uint32_t>(h >> 32)};
}

struct PixelSample {
    float x, y;  // offset inside the pixel, each in [0, 1)
};

// Sample `index` of the pixel keyed by `pixel_key` rendered at `count`
// samples: with one sample, the pixel centre (spec §3); otherwise dimensions
// (0, 1) of the pixel's group 0, which do not depend on `count`: the first
// n samples are the same whatever count ≥ n was asked, and the first 2^k
// are a (0, k, 2)-net over the pixel (spec §18).
inline PixelSample pixel_sample(std::uint32_t index, std::uint32_t count, std::uint64_t pixel_key) {
    if (count <= 1) return {0.5f, 0.5f};
    const sobol::Group g = sample_group(pixel_key, 0);
    const std::uint32_t s = g.shuffled_reversed(index);
    return {g.value_at(s, 0), g.value_at(s, 1)};
}

// The random numbers of one sample (pixel, sample index) beyond its position
// in the pixel: each call draws a new dimension.
//
// From 2 samples per pixel on the draws are progressive, Owen-scrambled
// Sobol. The stream walks the pixel's dimensions after the two its position
// takes (group 0's dimensions 2 and 3, then groups 1, 2, … of four, each an
// independently seeded sequence): a 1-D draw takes the next dimension, a
// 2-D draw the dimensions (0, 1) of the next group, the one pair of the four
// that is a (0, 2)-sequence (the pair (2, 3) is stratified only in its 1-D
// projections: see sampler_test.cpp). The path integrator's draws per
// vertex, 2-D, 1-D, 2-D, 1-D, 1-D, use two groups: a light's point then
// the choice of that light, a BSDF direction then its lobe, so that each
// choice is dimension 2 of its point's group and the two are stratified
// together. `count` only chooses
// this mode: a sample's numbers do not depend on how many samples the pixel
// takes (spec §18). With one sample per pixel every draw is an independent
// uniform hash, as in version 1, so that 1-spp images stay bit for bit.
struct SampleStream {
    static constexpr std::uint32_t kPixelDimensions = 2;  // group 0's (0, 1): the position in the pixel

    std::uint64_t pixel_key = 0;
    std::uint32_t index = 0;      // this sample's index among the pixel's
    std::uint32_t count = 1;      // the pixel's samples: 1, or more (progressive)
    std::uint32_t dimension = 0;  // draws so far (one sample); progressive: dimensions walked after the pixel's
    // Progressive: the group the last draw read, its seeds and this sample's
    // shuffled index in it, kept because a vertex reads each of its groups
    // two or three times (a point, then a choice or roulette). Not part of
    // what the sample is: every value is the same without it.
    std::uint32_t cached_group = 0xffffffffu;
    sobol::Group group{};
    std::uint32_t shuffled = 0;

    // A draw's place in the stream. A path vertex takes the same dimensions
    // whether it uses them or not (so that dimension k means the same thing
    // on every path), but computes only the values it reads: read_1d and
    // read_2d return what next_1d and next_2d would have returned at the
    // take.
    struct Slot {
        std::uint32_t dimension;  // one sample: the draw's count; progressive: the stream dimension
    };
    struct Pair {
        float u1, u2;
    };

    Slot take_1d() {
        if (count <= 1) return {++dimension};
        return {kPixelDimensions + dimension++};
    }
    Slot take_2d() {
        if (count <= 1) return {++dimension};
        std::uint32_t d = kPixelDimensions + dimension;
        d = (d + sobol::kDimensions - 1) / sobol::kDimensions * sobol::kDimensions;  // the next group's (0, 1)
        dimension = d + 2 - kPixelDimensions;
        return {d};
    }
    float read_1d(Slot slot) {
        if (count <= 1) return hash_to_unit(index, dimension_key(slot.dimension));
        select_group(slot.dimension / sobol::kDimensions);
        return group.value_at(shuffled, static_cast<int>(slot.dimension % sobol::kDimensions));
    }
    Pair read_2d(Slot slot) {
        if (count <= 1) return hashed_pair(dimension_key(slot.dimension));
        select_group(slot.dimension / sobol::kDimensions);
        return {group.value_at(shuffled, 0), group.value_at(shuffled, 1)};
    }

    float next_1d() { return read_1d(take_1d()); }
    Pair next_2d() { return read_2d(take_2d()); }

    // The thin lens's point (spec §17): a 2-D dimension of its own, keyed
    // apart from the sequence next_1d and next_2d walk (progressive: the
    // dimensions (0, 1) of a group of its own), so that opening the aperture
    // leaves every other draw of the sample as it was.
    Pair lens_2d() const {
        const std::uint64_t key = mix64(pixel_key ^ 0x6c656e73ull * 0x9e3779b97f4a7c15ull);
        if (count <= 1) return hashed_pair(key);
        const std::uint64_t h = mix64(key);
        const sobol::Group g{static_cast<std::uint32_t>(h), static_cast<std::uint32_t>(h >> 32)};
        const std::uint32_t s = g.shuffled_reversed(index);
        return {g.value_at(s, 0), g.value_at(s, 1)};
    }

private:
    void select_group(std::uint32_t g) {
        if (g == cached_group) return;
        cached_group = g;
        group = sample_group(pixel_key, g);
        shuffled = group.shuffled_reversed(index);
    }

    Pair hashed_pair(std::uint64_t key) const {
        return {hash_to_unit(index, key), hash_to_unit(index, key ^ 0x368cc8b700000000ull)};
    }

    std::uint64_t dimension_key(std::uint32_t draw) const {
        return mix64(pixel_key ^ (static_cast<std::uint64_t>(draw) * 0x9e3779b97f4a7c15ull));
    }
};

// The key that seeds pixel (i, j)'s samples for a render seed.
inline std::uint64_t pixel_key(std::uint64_t seed, int i, int j, int width) {
    return mix64(mix64(seed) ^
                 (static_cast<std::uint64_t>(j) * static_cast<std::uint64_t>(width) + static_cast<std::uint64_t>(i)));
}

}  // namespace sombra
