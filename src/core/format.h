// Numbers as text for messages and tables, one spelling everywhere.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <system_error>

namespace sombra {

// The shortest text that reads back to exactly `v` ("0.5", "1e+30", "-0.2"):
// a float prints as the float it is (0.2f is "0.2", not 0.200000003).
inline std::string format_number(double v) {
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return ec == std::errc{} ? std::string(buf, end) : std::to_string(v);
}
inline std::string format_number(float v) {
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return ec == std::errc{} ? std::string(buf, end) : std::to_string(v);
}

// An integer with thousands separators: 871414 → "871,414".
inline std::string thousands(std::uint64_t n) {
    const std::string digits = std::to_string(n);
    std::string out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

}  // namespace sombra
