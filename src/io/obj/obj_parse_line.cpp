// One line of an OBJ, for obj_parse.cpp: its numbers, read as tinyobjloader
// decides what a number is, and its face corners, resolved as tinyobjloader
// resolved them, with the index problems sombra reports first.
#include "io/obj/obj_parse.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>
#include <string_view>
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
    return static_cast<int>(static_cast<std::uint32_t>(as_long));        // atoi's cut to int
}

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

constexpr std::int64_t kBeyondInt32 = std::int64_t{0x7fffffff} + 1;

// The common corner forms, v, v/vt, v//vn and v/vt/vn with 1 to 9 digits
// each, none 0, no position before the first: nothing to check further, and
// tinyobjloader reads them the same. False (corners untouched) for anything else.
bool read_plain_corners(const char* p, const char* end, const ObjIndexCounts& before, std::vector<ObjCorner>& corners) {
    const std::size_t first = corners.size();
    auto part = [&](std::int64_t& value) {
        const bool negative = p != end && *p == '-';
        p += negative;
        const char* digits = p;
        std::int64_t v = 0;
        while (p != end && is_digit(*p) && p - digits < 10) v = v * 10 + (*p++ - '0');
        if (p == digits || p - digits > 9 || v == 0) return false;
        value = negative ? -v : v;
        return true;
    };
    auto at_corner_end = [&] { return p == end || is_blank(*p); };
    for (;;) {
        while (p != end && is_blank(*p)) ++p;
        if (p == end) return true;
        std::int64_t v = 0, vt = 0, vn = 0;
        bool ok = part(v);
        if (ok && p != end && *p == '/') {
            ++p;
            if (p != end && *p == '/') {
                ++p;
                ok = part(vn);
            } else {
                ok = part(vt);
                if (ok && p != end && *p == '/') {
                    ++p;
                    ok = part(vn);
                }
            }
        }
        const std::int64_t position = v > 0 ? v - 1 : before.positions + v;
        if (!ok || !at_corner_end() || position < 0) {
            corners.resize(first);
            return false;
        }
        const std::int64_t normal = vn > 0 ? vn - 1 : (vn < 0 ? before.normals + vn : -1);
        const std::int64_t texcoord = vt > 0 ? vt - 1 : (vt < 0 ? before.texcoords + vt : -1);
        corners.push_back({position, normal, texcoord});
    }
}

// Text from the file, quoted in a message: cut short, raw bytes shown as '?'.
std::string quoted(std::string_view text) {
    std::string out;
    for (char c : text.substr(0, 24)) out += c >= 0x20 && c < 0x7f ? c : '?';
    return text.size() > 24 ? out + "..." : out;
}

// An index spelled as a sign and digits; the magnitude saturates just beyond INT32_MAX.
struct SpelledIndex {
    std::int64_t value;
    std::string_view spelled;
};

bool leading_integer(std::string_view part, SpelledIndex& out) {
    std::size_t i = 0;
    const bool negative = i < part.size() && part[i] == '-';
    if (i < part.size() && (part[i] == '+' || part[i] == '-')) ++i;
    const std::size_t first_digit = i;
    std::int64_t value = 0;
    for (; i < part.size() && is_digit(part[i]); ++i)
        value = std::min<std::int64_t>(value * 10 + (part[i] - '0'), kBeyondInt32);
    if (i == first_digit) return false;
    out = {negative ? -value : value, part.substr(0, i)};
    return true;
}

// A part that atoi reads as 0 (no digits, no white space it would skip).
bool not_a_number(std::string_view part) {
    return !part.empty() && std::string_view(" \t\n\v\f\r").find(part[0]) == std::string_view::npos;
}

// The first unusable index of the line, checked per blank-separated corner
// and per '/'-separated part: sombra's own rules, which come before tinyobjloader's.
bool find_index_problem(std::string_view args, std::int64_t positions_before, ObjLineProblem& problem) {
    static constexpr const char* kIndexName[3] = {"face index", "texture coordinate index", "normal index"};
    std::size_t i = 0;
    while (i < args.size()) {
        while (i < args.size() && is_blank(args[i])) ++i;
        std::size_t j = i;
        while (j < args.size() && !is_blank(args[j])) ++j;
        const std::string_view corner = args.substr(i, j - i);
        i = j;
        std::size_t begin = 0;
        for (int part = 0; part < 3 && !corner.empty(); ++part) {
            std::size_t stop = corner.find('/', begin);
            if (stop == std::string_view::npos) stop = corner.size();
            const std::string_view spelled = corner.substr(begin, stop - begin);
            SpelledIndex index{};
            if (!leading_integer(spelled, index)) {
                if (not_a_number(spelled)) {
                    problem = {"face corner '" + quoted(corner) +
                               "' is not made of indices (v, v/vt, v//vn or v/vt/vn)"};
                    return true;
                }
            } else {
                const std::int64_t value = index.value;
                const bool huge = value >= kBeyondInt32 || value <= -kBeyondInt32;
                const bool before_first = part == 0 && value < 0 && -value > positions_before;
                if (value == 0 || huge || before_first) {
                    const std::string named = std::string(kIndexName[part]) + " " + quoted(index.spelled);
                    problem.part = part;
                    problem.needs_total = huge;
                    problem.what = value == 0 ? named + " is not allowed (OBJ indices start at 1)"
                                   : huge     ? named + " out of range"
                                              : named + " out of range (counting back from the " +
                                                std::to_string(positions_before) +
                                                (positions_before == 1 ? " vertex" : " vertices") + " before it)";
                    return true;
                }
            }
            if (stop == corner.size()) break;
            begin = stop + 1;
        }
    }
    return false;
}

const char* skip_index(const char* p, const char* end) {
    while (p != end && *p != '/' && !is_blank(*p)) ++p;  // strcspn(p, "/ \t\r")
    return p;
}

// tinyobjloader's parseTriple: position, then "/vt", "//vn" or "/vt/vn", each
// read with atoi (which skips white space, even past the corner). False on a 0.
bool read_triple(const char*& p, const char* end, int& v, int& vt, int& vn) {
    vt = 0;
    vn = 0;
    if ((v = obj_atoi(p, end)) == 0) return false;
    p = skip_index(p, end);
    if (p == end || *p != '/') return true;
    ++p;
    if (p != end && *p == '/') {
        ++p;
        if ((vn = obj_atoi(p, end)) == 0) return false;
        p = skip_index(p, end);
        return true;
    }
    if ((vt = obj_atoi(p, end)) == 0) return false;
    p = skip_index(p, end);
    if (p == end || *p != '/') return true;
    ++p;
    if ((vn = obj_atoi(p, end)) == 0) return false;
    p = skip_index(p, end);
    return true;
}

}  // namespace

ObjLineStatus read_obj_face(const char* args, const char* end, const ObjIndexCounts& before,
                            std::vector<ObjCorner>& corners, ObjLineProblem& problem) {
    corners.clear();
    if (read_plain_corners(args, end, before, corners)) return ObjLineStatus::Ok;
    if (find_index_problem(std::string_view(args, std::size_t(end - args)), before.positions, problem))
        return ObjLineStatus::IndexProblem;
    const char* p = args;
    while (p != end && is_blank(*p)) ++p;
    const char* corner = p;  // the blank-separated corner being read, for the message
    while (p != end) {
        int v = 0, vt = 0, vn = 0;
        if (!read_triple(p, end, v, vt, vn)) {
            const char* stop = corner;
            while (stop != end && !is_blank(*stop)) ++stop;
            problem = {"face corner '" + quoted(std::string_view(corner, std::size_t(stop - corner))) +
                       "' is not made of indices (v, v/vt, v//vn or v/vt/vn)"};
            return ObjLineStatus::Unreadable;
        }
        // fixIndex: 1-based, or negative counting back from what came before.
        const std::int64_t position = v > 0 ? v - 1 : before.positions + v;
        const std::int64_t normal = vn > 0 ? vn - 1 : (vn < 0 ? before.normals + vn : -1);
        const std::int64_t texcoord = vt > 0 ? vt - 1 : (vt < 0 ? before.texcoords + vt : -1);
        corners.push_back({position, normal, texcoord});
        const char* read = p;
        while (p != end && is_blank(*p)) ++p;
        if (p != read) corner = p;
    }
    return ObjLineStatus::Ok;
}

bool obj_index_line_readable(const char* args, const char* end) {
    const char* p = args;  // no blanks skipped first: tinyobjloader's atoi skips them
    while (p != end) {
        int v = 0, vt = 0, vn = 0;
        if (!read_triple(p, end, v, vt, vn)) return false;
        while (p != end && is_blank(*p)) ++p;
    }
    return true;
}

std::string obj_total_suffix(int part, std::int64_t total) {
    static constexpr const char* kElementName[3][2] = {
        {"vertex", "vertices"}, {"texture coordinate", "texture coordinates"}, {"normal", "normals"}};
    return " (the file has " + std::to_string(total) + " " + kElementName[part][total != 1] + ")";
}

}  // namespace sombra
