#include "scene/obj_scan.h"

#include <algorithm>

namespace sombra {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// Calls visit(content, line_number) for each line, the content cut at the
// first NUL as tinyobjloader (which reads it as a C string) sees it.
template <class Visit>
void for_each_line(std::string_view text, Visit&& visit) {
    const std::size_t size = text.size();
    std::size_t begin = 0;
    std::uint32_t line = 0;
    while (begin < size) {
        std::size_t end = begin;
        while (end < size && text[end] != '\n' && text[end] != '\r') ++end;
        ++line;
        std::string_view content = text.substr(begin, end - begin);
        if (const std::size_t nul = content.find('\0'); nul != std::string_view::npos) content = content.substr(0, nul);
        visit(content, line);
        begin = end + ((end + 1 < size && text[end] == '\r' && text[end + 1] == '\n') ? 2 : 1);
    }
}

// The line's keyword and arguments when it is "KEY args" (after leading blanks).
bool split_keyword(std::string_view content, char key, std::string_view& args) {
    std::size_t i = 0;
    while (i < content.size() && is_blank(content[i])) ++i;
    if (i + 1 >= content.size() || content[i] != key || !is_blank(content[i + 1])) return false;
    args = content.substr(i + 2);
    return true;
}

// Splits at runs of blanks; calls token(t) for each non-empty piece until it returns false.
template <class Token>
void for_each_token(std::string_view args, Token&& token) {
    std::size_t i = 0;
    while (i < args.size()) {
        while (i < args.size() && is_blank(args[i])) ++i;
        std::size_t j = i;
        while (j < args.size() && !is_blank(args[j])) ++j;
        if (j > i && !token(args.substr(i, j - i))) return;
        i = j;
    }
}

// Numbers contain digits, signs, '.', 'e'; nan, inf and MSVC's 1.#IND / 1.#INF do not.
bool spells_non_finite(std::string_view token) { return token.find_first_of("nNiI#") != std::string_view::npos; }

}  // namespace

std::vector<std::uint32_t> find_non_finite_vertices(std::string_view text) {
    std::vector<std::uint32_t> found;
    std::uint32_t vertex = 0;
    for_each_line(text, [&](std::string_view content, std::uint32_t) {
        std::string_view args;
        if (!split_keyword(content, 'v', args)) return;
        int coordinate = 0;
        bool bad = false;
        // tinyobjloader reads x, y, z from the first three tokens.
        for_each_token(args, [&](std::string_view token) {
            bad |= spells_non_finite(token);
            return ++coordinate < 3;
        });
        if (bad) found.push_back(vertex);
        ++vertex;
    });
    return found;
}

std::vector<ObjFaceLine> scan_obj_faces(std::string_view text) {
    std::vector<ObjFaceLine> faces;
    for_each_line(text, [&](std::string_view content, std::uint32_t line) {
        std::string_view args;
        if (!split_keyword(content, 'f', args)) return;
        std::uint32_t corners = 0;
        for_each_token(args, [&](std::string_view) {
            ++corners;
            return true;
        });
        if (corners >= 3) faces.push_back({line, corners});
    });
    return faces;
}

void comment_out_skin_weights(std::span<char> text) {
    const std::string_view view(text.data(), text.size());
    for_each_line(view, [&](std::string_view content, std::uint32_t) {
        std::size_t i = 0;
        while (i < content.size() && is_blank(content[i])) ++i;
        if (i + 2 < content.size() && content[i] == 'v' && content[i + 1] == 'w' && is_blank(content[i + 2]))
            text[static_cast<std::size_t>(content.data() - view.data()) + i] = '#';
    });
}

namespace {

// An index as tinyobjloader's atoi reads it: an optional sign, then digits,
// anything after them ignored. `spelled` is that prefix; nullopt without digits.
// The magnitude saturates just beyond INT32_MAX, the largest atoi gets right.
struct SpelledIndex {
    std::int64_t value;
    std::string_view spelled;
};
constexpr std::int64_t kBeyondInt32 = std::int64_t{0x7fffffff} + 1;

std::optional<SpelledIndex> leading_integer(std::string_view part) {
    std::size_t i = 0;
    const bool negative = i < part.size() && part[i] == '-';
    if (i < part.size() && (part[i] == '+' || part[i] == '-')) ++i;
    const std::size_t first_digit = i;
    std::int64_t value = 0;
    for (; i < part.size() && part[i] >= '0' && part[i] <= '9'; ++i)
        value = std::min<std::int64_t>(value * 10 + (part[i] - '0'), kBeyondInt32);
    if (i == first_digit) return std::nullopt;
    return SpelledIndex{negative ? -value : value, part.substr(0, i)};
}

// Text from the file, quoted in a message: cut short, raw bytes shown as '?'.
std::string quoted(std::string_view text) {
    std::string out;
    for (char c : text.substr(0, 24)) out += c >= 0x20 && c < 0x7f ? c : '?';
    return text.size() > 24 ? out + "..." : out;
}

// A part that atoi reads as 0 (no digits, no blank it would skip): tinyobjloader rejects the face.
bool not_a_number(std::string_view part) {
    return !part.empty() && std::string_view(" \t\n\v\f\r").find(part[0]) == std::string_view::npos;
}

}  // namespace

std::optional<ObjIndexProblem> find_bad_face_index(std::string_view text) {
    // Corner parts in order v/vt/vn, and what the file defines of each so far.
    static constexpr const char* kIndexName[3] = {"face index", "texture coordinate index", "normal index"};
    static constexpr const char* kElementName[3][2] = {
        {"vertex", "vertices"}, {"texture coordinate", "texture coordinates"}, {"normal", "normals"}};
    std::int64_t defined[3] = {0, 0, 0};
    std::optional<ObjIndexProblem> problem;
    int problem_part = 0;
    bool needs_total = false;  // the message ends with the file's total count of that element

    for_each_line(text, [&](std::string_view content, std::uint32_t line) {
        std::size_t i = 0;
        while (i < content.size() && is_blank(content[i])) ++i;
        const std::string_view rest = content.substr(i);
        if (rest.size() >= 2 && rest[0] == 'v') {
            if (is_blank(rest[1])) ++defined[0];
            else if (rest.size() >= 3 && rest[1] == 't' && is_blank(rest[2])) ++defined[1];
            else if (rest.size() >= 3 && rest[1] == 'n' && is_blank(rest[2])) ++defined[2];
            return;
        }
        std::string_view args;
        if (problem || !split_keyword(content, 'f', args)) return;
        for_each_token(args, [&](std::string_view corner) {
            std::size_t begin = 0;
            for (int part = 0; part < 3; ++part) {
                std::size_t end = corner.find('/', begin);
                if (end == std::string_view::npos) end = corner.size();
                const std::string_view spelled = corner.substr(begin, end - begin);
                const auto index = leading_integer(spelled);
                if (!index && not_a_number(spelled)) {
                    problem = ObjIndexProblem{line, "face corner '" + quoted(corner) +
                                                        "' is not made of indices (v, v/vt, v//vn or v/vt/vn)"};
                    return false;
                }
                if (index) {
                    const std::int64_t value = index->value;
                    const bool zero = value == 0;
                    const bool huge = value >= kBeyondInt32 || value <= -kBeyondInt32;
                    const bool before_first = part == 0 && value < 0 && -value > defined[0];
                    if (zero || huge || before_first) {
                        const std::string named = std::string(kIndexName[part]) + " " + quoted(index->spelled);
                        problem = ObjIndexProblem{
                            line, zero   ? named + " is not allowed (OBJ indices start at 1)"
                                  : huge ? named + " out of range"
                                         : named + " out of range (counting back from the " +
                                               std::to_string(defined[0]) +
                                               (defined[0] == 1 ? " vertex" : " vertices") + " before it)"};
                        problem_part = part;
                        needs_total = huge;
                        return false;
                    }
                }
                if (end == corner.size()) break;
                begin = end + 1;
            }
            return true;
        });
    });
    if (problem && needs_total) {
        const std::int64_t total = defined[problem_part];
        problem->what += " (the file has " + std::to_string(total) + " " + kElementName[problem_part][total != 1] + ")";
    }
    return problem;
}

}  // namespace sombra
