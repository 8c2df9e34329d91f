// Linear float → 8-bit sRGB code at the speed of two table lookups, exactly
// as encode_srgb8 (writers.h) rounds, without the pow() per channel that
// would otherwise dominate writing a PNG.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

namespace sombra {

class Srgb8Table {
public:
    Srgb8Table();

    std::uint8_t encode(float linear) const {
        if (!(linear > 0.0f)) return 0;  // also NaN
        if (linear >= 1.0f) return 255;
        std::uint32_t bits = 0;
        std::memcpy(&bits, &linear, sizeof bits);
        // Within one bucket of equal top 16 bits the code rises by at most
        // one (checked when the table is built): the bucket's first code,
        // plus one past the next code's threshold.
        const std::uint8_t first = bucket_code_[bits >> 16];
        return static_cast<std::uint8_t>(first + (linear >= threshold_[first + 1u] ? 1 : 0));
    }

private:
    static constexpr std::size_t kBuckets = (0x3f800000u >> 16) + 1;  // the top 16 bits of floats in [0, 1]
    std::array<std::uint8_t, kBuckets> bucket_code_{};                // encode_srgb8 of each bucket's smallest float
    std::array<float, 257> threshold_{};  // threshold_[k]: the smallest float whose code is k (k ≥ 1); [256] = +∞
};

}  // namespace sombra
