// One `f`, `l` or `p` line of an OBJ (obj_parse.cpp's per-line part): the
// corner indices as tinyobjloader resolved them, and the index problems
// sombra reports before anything else (0, beyond 32 bits, before the first
// vertex, not a number).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sombra {

// A corner's indices, 0-based and resolved (negative ones relative to what
// came before); normal -1 when the corner names none. Either may lie
// outside the file's arrays: the caller checks them against the totals.
struct ObjCorner {
    std::int64_t position;
    std::int64_t normal;
};

struct ObjIndexCounts {
    std::int64_t positions = 0;  // `v` lines before this line
    std::int64_t normals = 0;    // `vn` lines before this line
};

enum class ObjLineStatus {
    Ok,            // `corners` holds the face's corners (maybe fewer than 3)
    IndexProblem,  // `problem` says which index, as the error message
    Unreadable,    // tinyobjloader would stop here: `problem` says why
};

struct ObjLineProblem {
    std::string what;
    int part = 0;             // 0 position, 1 texture coordinate, 2 normal
    bool needs_total = false; // the message ends with the file's count of that part
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

}  // namespace sombra
