#include "scene/obj_scan.h"

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

}  // namespace sombra
