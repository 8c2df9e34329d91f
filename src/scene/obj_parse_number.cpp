#include "scene/obj_parse_number.h"

#include <charconv>
#include <cstdint>
#include <limits>
#include <system_error>

namespace sombra {
namespace {

bool is_digit(char c) { return static_cast<unsigned char>(c - '0') < 10; }

// ±inf or ±0 for a decimal that even double cannot hold (beyond 1e±308):
// which of the two follows from the decimal exponent of its first significant digit.
float beyond_double(const char* first, const char* last, bool negative) {
    const char* c = first;
    if (c != last && (*c == '+' || *c == '-')) ++c;
    long long integer_digits = 0, zeros_after_dot = 0;
    bool after_dot = false, significant = false;
    for (; c != last && (is_digit(*c) || *c == '.'); ++c) {
        if (*c == '.') {
            after_dot = true;
        } else if (!after_dot) {
            significant |= *c != '0';
            integer_digits += significant;
        } else if (!significant) {
            if (*c != '0') break;
            ++zeros_after_dot;
        }
    }
    while (c != last && *c != 'e' && *c != 'E') ++c;
    long long exponent = 0;
    if (c != last) {
        ++c;
        const bool minus = c != last && *c == '-';
        if (c != last && (*c == '+' || *c == '-')) ++c;
        for (; c != last && is_digit(*c); ++c) exponent = exponent * 10 + (*c - '0');  // at most 9 digits
        if (minus) exponent = -exponent;
    }
    const long long magnitude = (significant ? integer_digits : -zeros_after_dot) + exponent;
    const float out = magnitude > 0 ? std::numeric_limits<float>::infinity() : 0.0f;
    return negative ? -out : out;
}

}  // namespace

const char* read_obj_real(const char* first, const char* last, float& value) {
    if (first >= last) return nullptr;
    const char* c = first;
    bool negative = false, leading_dot = false;
    if (*c == '+' || *c == '-') {
        negative = *c == '-';
        ++c;
        leading_dot = c != last && *c == '.';
    } else if (*c == '.') {
        leading_dot = true;
    } else if (!is_digit(*c)) {
        return nullptr;
    }
    // The digits' value while it fits: most coordinates take the fast path below.
    std::uint64_t mantissa = 0;
    int digits = 0, fraction_digits = 0;
    auto read_digits = [&](const char* from) {
        for (; c != last && is_digit(*c); ++c) {
            if (digits < 19) mantissa = mantissa * 10 + std::uint64_t(*c - '0');
            ++digits;
        }
        return c != from;
    };
    bool any_digit = false;
    if (!leading_dot) {
        if (!read_digits(c)) return nullptr;  // a sign alone
        any_digit = true;
    }
    bool exponent_part = false;
    if (c != last && *c == '.') {
        ++c;
        const int before = digits;
        any_digit |= read_digits(c);
        fraction_digits = digits - before;
    }
    if (c != last && (*c == 'e' || *c == 'E')) {
        exponent_part = true;
        ++c;
        if (c != last && (*c == '+' || *c == '-')) ++c;
        const char* exponent_digits = c;
        int exponent = 0;
        for (; c != last && is_digit(*c); ++c) {
            if (exponent > 214748364) return nullptr;  // tinyobjloader's int overflow guard
            exponent = exponent * 10 + (*c - '0');
        }
        if (c == exponent_digits) return nullptr;  // "1e", "1e+": tinyobjloader rejects the whole number
    }
    if (!any_digit) {  // ".", "-.", ".e5": no digits, tinyobjloader's mantissa stays 0
        value = negative ? -0.0f : 0.0f;
        return c;
    }
    // Clinger's fast path: an integer below 2^24 and a power of ten up to 10^10
    // are exact floats, so their IEEE quotient is the correctly rounded value.
    static constexpr float kPow10[11] = {1e0f, 1e1f, 1e2f, 1e3f, 1e4f, 1e5f, 1e6f, 1e7f, 1e8f, 1e9f, 1e10f};
    if (!exponent_part && digits <= 19 && mantissa <= (std::uint64_t{1} << 24) && fraction_digits <= 10) {
        const float magnitude = static_cast<float>(mantissa) / kPow10[fraction_digits];
        value = negative ? -magnitude : magnitude;
        return c;
    }
    const char* start = *first == '+' ? first + 1 : first;  // from_chars takes no '+'
    float f = 0;
    const auto [end, ec] = std::from_chars(start, c, f);
    if (ec == std::errc::result_out_of_range) {
        // Outside float's range: the double rounds to the same ±inf or ±0 strtof gives.
        double d = 0;
        const auto [dend, dec] = std::from_chars(start, c, d);
        f = dec == std::errc() ? static_cast<float>(d) : beyond_double(start, c, negative);
    } else if (ec != std::errc() || end != c) {
        return nullptr;  // not reached: the grammar above is a subset of from_chars'
    }
    value = f;
    return c;
}

int obj_atoi(const char* first, const char* last) {
    const char* c = first;
    while (c != last && (*c == ' ' || (*c >= '\t' && *c <= '\r'))) ++c;
    bool negative = false;
    if (c != last && (*c == '+' || *c == '-')) negative = *c++ == '-';
    // strtol's value, saturated at the long range as glibc does.
    constexpr std::uint64_t kLongMax = std::uint64_t(std::numeric_limits<std::int64_t>::max());
    const std::uint64_t limit = negative ? kLongMax + 1 : kLongMax;
    std::uint64_t magnitude = 0;
    for (; c != last && is_digit(*c); ++c) {
        const std::uint64_t digit = std::uint64_t(*c - '0');
        magnitude = magnitude > (limit - digit) / 10 ? limit : magnitude * 10 + digit;
    }
    const std::uint64_t as_long = negative ? 0 - magnitude : magnitude;  // two's complement
    return static_cast<int>(static_cast<std::uint32_t>(as_long));       // atoi's cut to int
}

}  // namespace sombra
