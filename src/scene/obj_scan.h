// What sombra reads from an OBJ's text itself, beside tinyobjloader: facts
// tinyobjloader loses (it reads "nan" and "inf" as finite numbers and keeps a
// face's corner count in one byte) and the line of each face, for messages.
// Lines are numbered as tinyobjloader numbers them (ends: \n, \r\n or \r).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sombra {

// 0-based numbers of the `v` lines with a coordinate spelled as nan or inf
// ("nan", "-inf", "1.#IND", "1.#INF", …), in file order; usually empty.
std::vector<std::uint32_t> find_non_finite_vertices(std::string_view text);

struct ObjFaceLine {
    std::uint32_t line;     // 1-based line number
    std::uint32_t corners;  // corner count, 3 or more
};

// Every `f` line with 3 or more corners (the faces tinyobjloader keeps), in file order.
std::vector<ObjFaceLine> scan_obj_faces(std::string_view text);

// Turns every `vw` line (skin weights, a tinyobjloader extension sombra does
// not use) into a comment, keeping the line numbers: tinyobjloader converts
// their joint ids to int unchecked, undefined for 1e38 or nan (found by fuzz_obj).
void comment_out_skin_weights(std::span<char> text);

struct ObjIndexProblem {
    std::uint32_t line;  // 1-based line number of the `f` line
    std::string what;    // e.g. "face index 0 is not allowed (OBJ indices start at 1)"
};

// The first face corner index that tinyobjloader would misread or reject
// without saying which: 0, beyond 32 bits (its atoi wraps them to a valid
// index), or a negative (relative) vertex index reaching before the first
// vertex. std::nullopt when every index is usable or is left for the loader
// to check against the final counts.
std::optional<ObjIndexProblem> find_bad_face_index(std::string_view text);

}  // namespace sombra
