// e^(−x) for x ≥ 0, to a few 10⁻⁶ relative: the non-local-means weights
// take hundreds of these a pixel, and this form (plain arithmetic, no
// branch, no call) lets the compiler do eight at once where libm does one.
#pragma once

#include <bit>
#include <cstdint>

namespace sombra {

inline float exp_negative(float x) {
    // e^(−x) = 2^t with t = −x·log2(e) = n + f, n the nearest integer,
    // |f| ≤ 1/2; below 2^−126 the result is 0 (a normal float's floor).
    const float t0 = -x * 1.44269504089f;
    const float t = t0 < -126.0f ? -126.0f : t0;
    // Adding 1.5·2^23 leaves round(t) in the sum's low bits.
    constexpr float kRound = 12582912.0f;
    const float shifted = t + kRound;
    const float n = shifted - kRound;
    const float f = t - n;
    // 2^f = e^(f·ln 2) by its Taylor series to the 7th power (|f·ln 2| ≤ 0.35).
    float p = 1.52527338e-05f;
    p = p * f + 1.54035304e-04f;
    p = p * f + 1.33335581e-03f;
    p = p * f + 9.61812911e-03f;
    p = p * f + 5.55041087e-02f;
    p = p * f + 2.40226507e-01f;
    p = p * f + 6.93147181e-01f;
    p = p * f + 1.0f;
    const std::int32_t power = std::bit_cast<std::int32_t>(shifted) - std::bit_cast<std::int32_t>(kRound);
    const float value = p * std::bit_cast<float>(static_cast<std::uint32_t>(power + 127) << 23);
    return n > -126.0f ? value : 0.0f;  // a choice between two values, not a branch
}

}  // namespace sombra
