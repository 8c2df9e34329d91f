// OBJ text → positions, normals, texture coordinates, faces and the
// material directives, in parallel over chunks of lines (spec §5, §9). What
// it reads and rejects is what tinyobjloader did for sombra before
// (objsuite/README.md), except that every error names its line and `usemtl`
// takes the rest of its line as the name; numbers are read the way
// tinyobjloader decides what a number is, but rounded correctly
// (std::from_chars, the same float strtof gives). MTL files are not read
// here. The per-line part (obj_parse_line.cpp) resolves one `f`, `l` or `p`
// line's corner indices and reports the index problems sombra checks first
// (0, beyond 32 bits, before the first vertex, not a number).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/vec2.h"
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
    std::vector<std::uint32_t> texcoords;  // per corner: index into ObjGeometry::texcoords, or kNoUv
    std::vector<std::uint32_t> ends;       // per face: one past its last corner
};

struct ObjGeometry {
    std::vector<Vec3> positions;  // every `v`, in file order; NaN where a coordinate is spelled nan/inf
    std::vector<Vec3> normals;    // every `vn`, in file order, as written
    std::vector<Vec2> texcoords;  // every `vt` (u, v; a third value ignored), in file order, as written
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

// A corner's indices, 0-based and resolved (negative ones relative to what
// came before); normal -1 when the corner names none. Either may lie
// outside the file's arrays: the caller checks them against the totals.
struct ObjCorner {
    std::int64_t position;
    std::int64_t normal;
    std::int64_t texcoord;  // -1 when the corner names none
};

struct ObjIndexCounts {
    std::int64_t positions = 0;  // `v` lines before this line
    std::int64_t normals = 0;    // `vn` lines before this line
    std::int64_t texcoords = 0;  // `vt` lines before this line
};

enum class ObjLineStatus {
    Ok,            // `corners` holds the face's corners (maybe fewer than 3)
    IndexProblem,  // `problem` says which index, as the error message
    Unreadable,    // tinyobjloader would stop here: `problem` says why
};

struct ObjLineProblem {
    std::string what;
    int part = 0;              // 0 position, 1 texture coordinate, 2 normal
    bool needs_total = false;  // the message ends with the file's count of that part
};

// Reads the corners of a face line: `args` is the text after "f" and its
// blank, `end` the end of the line's content.
ObjLineStatus read_obj_face(const char* args, const char* end, const ObjIndexCounts& before,
                            std::vector<ObjCorner>& corners, ObjLineProblem& problem);

// Checks an `l` or `p` line as tinyobjloader reads it (indices, none 0);
// `args` is the text after the keyword and its blank. False where it fails.
bool obj_index_line_readable(const char* args, const char* end);

// "face index 0 is not allowed ..."'s tail for a too large index: " (the file has N vertices)".
std::string obj_total_suffix(int part, std::int64_t total);

// Reads the longest prefix of [first, last) that tinyobjloader's
// tryParseDouble accepts: [sign] (digits | '.') [. digits] [e|E [sign] digits]
// ("3.1+e2" reads as 3.1, "1.#IND" as 1, "-." as -0). Returns the end of that
// prefix with `value` set to strtof's float for it (±inf beyond the float
// range), or nullptr where tinyobjloader fails ("nan", "1e", an exponent of
// more than 9 digits), leaving `value` unchanged.
const char* read_obj_real(const char* first, const char* last, float& value);

// C's atoi on [first, last) as glibc computes it: leading white space, a
// sign, digits; strtol saturates at 64 bits and the result is cut to int.
// tinyobjloader reads every face index this way.
int obj_atoi(const char* first, const char* last);

}  // namespace sombra
