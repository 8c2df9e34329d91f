#include "image/srgb8_table.h"

#include <limits>
#include <stdexcept>

#include "image/writers.h"

namespace sombra {

namespace {

float float_of(std::uint32_t bits) {
    float f = 0;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

}  // namespace

Srgb8Table::Srgb8Table() {
    // encode_srgb8 never falls as its argument rises, so each code's floats
    // form one interval: its start is found by bisection over the bit
    // patterns of [0, 1] (non-negative floats order as their bits do).
    threshold_[0] = 0.0f;
    for (std::uint32_t code = 1; code < 256; ++code) {
        std::uint32_t lo = 0, hi = 0x3f800000u;
        while (lo < hi) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            if (encode_srgb8(float_of(mid)) >= code)
                hi = mid;
            else
                lo = mid + 1;
        }
        threshold_[code] = float_of(lo);
    }
    threshold_[256] = std::numeric_limits<float>::infinity();
    for (std::uint32_t b = 0; b < kBuckets; ++b) {
        bucket_code_[b] = encode_srgb8(float_of(b << 16));
        // The bucket's last float must be at most one code above its first.
        const float last = b + 1 < kBuckets ? float_of(((b + 1) << 16) - 1) : 1.0f;
        if (b + 1 < kBuckets && encode_srgb8(last) > bucket_code_[b] + 1)
            throw std::logic_error("Srgb8Table: a bucket spans two code thresholds");
    }
}

}  // namespace sombra
