// fuzz_obj's second check: sombra's OBJ parser splits the text into chunks
// parsed in parallel, and promises the same result for any chunk size. The
// fuzzer runs each input through parse_obj with the default chunks (one, for
// inputs this small) and with tiny ones, and compares everything it returns.
#pragma once

#include <bit>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "io/obj/obj_parse.h"

namespace sombra::fuzz {

// The parse as comparable data: the error, or every field with faces flattened.
struct ObjParseOutcome {
    std::string error;
    std::vector<std::uint32_t> position_bits, normal_bits, texcoord_bits;  // floats as bits: NaN equals NaN
    std::vector<std::uint32_t> corner_positions, corner_normals, corner_texcoords, face_sizes;
    std::vector<std::string> directives;  // "kind line face text"
    std::size_t small_faces = 0, bad_normal_refs = 0;
    bool operator==(const ObjParseOutcome&) const = default;
};

inline ObjParseOutcome parse_obj_outcome(std::string_view text, std::size_t chunk_bytes) {
    ObjParseOutcome out;
    ObjGeometry g;
    try {
        g = parse_obj(text, "fuzz.obj", chunk_bytes);
    } catch (const Error& e) {
        out.error = e.what();
        return out;
    }
    for (const Vec3& p : g.positions)
        for (int k = 0; k < 3; ++k) out.position_bits.push_back(std::bit_cast<std::uint32_t>(p[k]));
    for (const Vec3& n : g.normals)
        for (int k = 0; k < 3; ++k) out.normal_bits.push_back(std::bit_cast<std::uint32_t>(n[k]));
    for (const Vec2& t : g.texcoords) {
        out.texcoord_bits.push_back(std::bit_cast<std::uint32_t>(t.x));
        out.texcoord_bits.push_back(std::bit_cast<std::uint32_t>(t.y));
    }
    for (const ObjFaceBlock& block : g.faces) {
        out.corner_positions.insert(out.corner_positions.end(), block.positions.begin(), block.positions.end());
        out.corner_normals.insert(out.corner_normals.end(), block.normals.begin(), block.normals.end());
        out.corner_texcoords.insert(out.corner_texcoords.end(), block.texcoords.begin(), block.texcoords.end());
        std::uint32_t begin = 0;
        for (std::uint32_t end : block.ends) {
            out.face_sizes.push_back(end - begin);
            begin = end;
        }
    }
    for (const ObjDirective& d : g.directives) {
        out.directives.push_back(std::to_string(int(d.kind)) + " " + std::to_string(d.line) + " " +
                                 std::to_string(d.face) + " " + std::string(d.text));
    }
    out.small_faces = g.small_faces;
    out.bad_normal_refs = g.bad_normal_refs;
    return out;
}

// "" when tiny chunks (1 to 97 bytes, picked by the input's size) parse
// `text` exactly as the default chunking does.
inline std::string obj_chunking_problem(std::string_view text) {
    const std::size_t tiny = 1 + text.size() % 97;
    if (parse_obj_outcome(text, tiny) == parse_obj_outcome(text, std::size_t{1} << 19)) return {};
    return "parse_obj differs with " + std::to_string(tiny) + "-byte chunks";
}

}  // namespace sombra::fuzz
