// The PLY header (ply_format.h): format, elements and their properties in
// file order, each line checked, errors at "file.ply:LINE".
#include <charconv>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "io/ply/ply_format.h"

namespace sombra {

namespace {

std::optional<PlyType> parse_type(std::string_view name) {
    struct Named {
        std::string_view name;
        PlyType type;
    };
    static constexpr Named kTypes[] = {
        {"char", PlyType::Int8},       {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},     {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16},   {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},     {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32},   {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64},
    };
    for (const Named& t : kTypes) {
        if (t.name == name) return t.type;
    }
    return std::nullopt;
}

std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        std::size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
        if (j > i) words.push_back(line.substr(i, j - i));
        i = j;
    }
    return words;
}

// A header word as it may be quoted in a message: short, and no raw binary bytes.
std::string printable(std::string_view word) {
    std::string out;
    for (char c : word.substr(0, 32)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    return word.size() > 32 ? out + "..." : out;
}

}  // namespace

std::size_t ply_type_size(PlyType type) {
    switch (type) {
        case PlyType::Int8:
        case PlyType::UInt8: return 1;
        case PlyType::Int16:
        case PlyType::UInt16: return 2;
        case PlyType::Int32:
        case PlyType::UInt32:
        case PlyType::Float32: return 4;
        case PlyType::Float64: return 8;
    }
    return 1;
}

int PlyElement::find(std::string_view property_name) const {
    for (std::size_t i = 0; i < properties.size(); ++i) {
        if (properties[i].name == property_name) return static_cast<int>(i);
    }
    return -1;
}

PlyHeader parse_ply_header(std::string_view text, const std::string& where) {
    PlyHeader header;
    bool have_format = false;
    std::size_t begin = 0;
    for (int line_number = 1;; ++line_number) {
        const std::string at = where + ":" + std::to_string(line_number);
        if (begin >= text.size()) {
            throw Error(at, line_number == 1 ? "empty file" : "the PLY header has no end_header line");
        }
        std::size_t end = text.find('\n', begin);
        const std::size_t next = end == std::string_view::npos ? text.size() : end + 1;
        std::string_view line = text.substr(begin, (end == std::string_view::npos ? text.size() : end) - begin);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        begin = next;

        if (line_number == 1) {
            while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
            if (line != "ply") throw Error(at, "not a PLY file (the first line must be 'ply')");
            continue;
        }
        const std::vector<std::string_view> words = split_words(line);
        if (words.empty()) continue;
        const std::string_view keyword = words[0];
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            if (!have_format) throw Error(at, "the PLY header has no format line");
            header.body_offset = next;
            header.body_line = line_number + 1;
            return header;
        }
        if (keyword == "format") {
            if (have_format) throw Error(at, "second format line");
            if (words.size() != 3)
                throw Error(at, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
            if (words[1] == "ascii") {
                header.format = PlyFormat::Ascii;
            } else if (words[1] == "binary_little_endian") {
                header.format = PlyFormat::BinaryLittleEndian;
            } else if (words[1] == "binary_big_endian") {
                header.format = PlyFormat::BinaryBigEndian;
            } else {
                throw Error(at, "unknown PLY format '" + std::string(words[1]) + "'");
            }
            if (words[2] != "1.0" && words[2] != "1") {
                throw Error(at, "unsupported PLY version '" + std::string(words[2]) + "' (expected 1.0)");
            }
            have_format = true;
        } else if (keyword == "element") {
            if (words.size() != 3) throw Error(at, "expected 'element NAME COUNT'");
            PlyElement element;
            element.name = words[1];
            element.line = line_number;
            const std::string_view count = words[2];
            const auto [ptr, ec] = std::from_chars(count.data(), count.data() + count.size(), element.count);
            if (ec != std::errc() || ptr != count.data() + count.size()) {
                throw Error(at, "element count '" + std::string(count) + "' is not a non-negative integer");
            }
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty()) throw Error(at, "property before any element");
            PlyProperty property;
            if (words.size() == 5 && words[1] == "list") {
                const auto count_type = parse_type(words[2]);
                const auto item_type = parse_type(words[3]);
                if (!count_type) throw Error(at, "unknown property type '" + std::string(words[2]) + "'");
                if (!item_type) throw Error(at, "unknown property type '" + std::string(words[3]) + "'");
                property.is_list = true;
                property.count_type = *count_type;
                property.type = *item_type;
                property.name = words[4];
            } else if (words.size() == 3 && words[1] != "list") {
                const auto type = parse_type(words[1]);
                if (!type) throw Error(at, "unknown property type '" + std::string(words[1]) + "'");
                property.type = *type;
                property.name = words[2];
            } else {
                throw Error(at, "expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
            }
            header.elements.back().properties.push_back(std::move(property));
        } else {
            throw Error(at, "unknown PLY header line '" + printable(keyword) + "'");
        }
    }
}

}  // namespace sombra
