// OBJ text → positions, normals, faces and the material directives, in
// parallel over chunks of lines (spec §5, §9). What it reads and rejects is
// what tinyobjloader did for sombra before (objsuite/README.md), except that
// every error names its line and `usemtl` takes the rest of its line as the
// name; the numbers are rounded correctly. MTL files are not read here.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/vec3.h"

namespace sombra {

// `usemtl NAME` or `mtllib FILES`, applied by the loader in file order.
struct ObjDirective {
    enum class Kind : std::uint8_t { Usemtl, Mtllib };
    Kind kind;
    std::size_t line;       // 1-based
    std::size_t face;       // faces (of 3 or more corners) before it in the file
    std::string_view text;  // usemtl: the name, trimmed; mtllib: the rest of the line as written
};

// One chunk's faces with 3 or more corners, in file order.
struct ObjFaceBlock {
    std::vector<std::uint32_t> positions;  // per corner: 0-based position index, < ObjGeometry::positions.size()
    std::vector<std::uint32_t> normals;    // per corner: index into ObjGeometry::normals, or kNoNormal
    std::vector<std::uint32_t> ends;       // per face: one past its last corner
};

struct ObjGeometry {
    std::vector<Vec3> positions;  // every `v`, in file order; NaN where a coordinate is spelled nan/inf
    std::vector<Vec3> normals;    // every `vn`, in file order, as written
    std::vector<ObjFaceBlock> faces;
    std::vector<ObjDirective> directives;  // views into the parsed text
    std::size_t small_faces = 0;           // `f` lines with fewer than 3 corners (skipped)
    std::size_t bad_normal_refs = 0;       // corners naming a normal the file does not define (dropped)
};

// Parses `text` (the file without a UTF-8 byte order mark); `where` (the
// path) prefixes errors. Lines end at \n, \r\n or \r and are cut at a NUL.
// Throws Error("where:LINE", ...) for the first unusable face index (0, out
// of range, not a number), else the first `f`/`l`/`p` line tinyobjloader
// could not read. `chunk_bytes` only sets the parallel split: the result is
// the same for any value and any thread count.
ObjGeometry parse_obj(std::string_view text, const std::string& where, std::size_t chunk_bytes = 1 << 19);

}  // namespace sombra
