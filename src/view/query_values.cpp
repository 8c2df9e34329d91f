#include "view/query_values.h"

#include <charconv>
#include <cmath>
#include <limits>

namespace sombra {

namespace {

// At most this many characters of a bad value go into a message.
constexpr std::size_t kQuoted = 40;

std::string quoted(std::string_view text) {
    std::string q(text.substr(0, kQuoted));
    for (char& c : q)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    return "'" + q + (text.size() > kQuoted ? "...'" : "'");
}

}  // namespace

std::optional<double> parse_query_number(std::string_view name, std::string_view text, std::string& problem) {
    double value = 0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc{} || stop != end || !std::isfinite(value) ||
        std::abs(value) > std::numeric_limits<float>::max()) {
        problem = std::string(name) + " must be a finite number, not " + quoted(text);
        return std::nullopt;
    }
    return value;
}

std::optional<int> parse_query_int(std::string_view name, std::string_view text, int least, int most,
                                   std::string& problem) {
    int value = 0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc{} || stop != end || value < least || value > most) {
        problem = std::string(name) + " must be an integer from " + std::to_string(least) + " to " +
                  std::to_string(most) + ", not " + quoted(text);
        return std::nullopt;
    }
    return value;
}

std::optional<Vec3> parse_query_vec3(std::string_view name, std::string_view text, std::string& problem) {
    float xyz[3] = {0, 0, 0};
    std::string_view rest = text;
    for (int c = 0; c < 3; ++c) {
        const std::size_t comma = rest.find(',');
        const bool last = c == 2;
        if (last != (comma == std::string_view::npos)) {
            problem = std::string(name) + " must be three numbers separated by commas, not " + quoted(text);
            return std::nullopt;
        }
        const std::optional<double> v = parse_query_number(name, rest.substr(0, comma), problem);
        if (!v) return std::nullopt;
        xyz[c] = static_cast<float>(*v);
        if (!last) rest.remove_prefix(comma + 1);
    }
    return Vec3{xyz[0], xyz[1], xyz[2]};
}

}  // namespace sombra
