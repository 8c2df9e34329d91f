// What sombra reads from an OBJ's text itself, beside tinyobjloader: facts
// tinyobjloader loses (it reads "nan" and "inf" as finite numbers and keeps a
// face's corner count in one byte) and the line of each face, for messages.
// Lines are numbered as tinyobjloader numbers them (ends: \n, \r\n or \r).
#pragma once

#include <cstdint>
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

}  // namespace sombra
