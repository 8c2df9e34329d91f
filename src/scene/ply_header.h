// The header of a PLY file (spec §9): format, and the elements with their
// properties in file order.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sombra {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

// Bytes of one value of `type` in a binary body.
std::size_t ply_type_size(PlyType type);

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;  // the value type; for a list, the type of its items
    bool is_list = false;
    PlyType count_type = PlyType::UInt8;  // lists only: the type of the leading item count
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;  // as claimed by the header: not yet checked against the body
    std::vector<PlyProperty> properties;
    int line = 0;  // header line declaring it

    // Index into properties of the property named `name`, or -1.
    int find(std::string_view property_name) const;
};

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    std::size_t body_offset = 0;  // byte offset of the body: just after the end_header line
    int body_line = 0;            // line number of the body's first line
};

// Parses the header at the start of `text`. Throws Error("WHERE:LINE", ...)
// for anything that is not a PLY 1.0 header, with `where` the file's path.
PlyHeader parse_ply_header(std::string_view text, const std::string& where);

}  // namespace sombra
