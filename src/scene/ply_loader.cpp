// PLY (ascii, binary little and big endian) → LoadedMesh (spec §9): vertex
// x, y, z (and nx, ny, nz when all three are there), face lists named
// vertex_indices or vertex_index; every other element and property skipped.
// Every count the header claims is checked against the bytes left before
// anything is reserved for it.
#include "scene/mesh_file.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/error.h"
#include "scene/mesh_builder.h"
#include "scene/ply_format.h"

namespace sombra {

namespace {

// Property indices in the vertex element; -1 when absent.
struct VertexLayout {
    int x = -1, y = -1, z = -1;
    int nx = -1, ny = -1, nz = -1;
    int u = -1, v = -1;  // texture coordinates: u v, s t or texture_u texture_v
    bool has_normals() const { return nx >= 0 && ny >= 0 && nz >= 0; }
    bool has_uvs() const { return u >= 0 && v >= 0; }
};

// Narrowing that stays defined for doubles beyond float's range.
float to_float(double value) {
    constexpr double kMax = std::numeric_limits<float>::max();
    if (value > kMax) return std::numeric_limits<float>::infinity();
    if (value < -kMax) return -std::numeric_limits<float>::infinity();
    return static_cast<float>(value);  // NaN stays NaN
}

template <class Cursor>
std::size_t min_record_size(const PlyElement& element) {
    std::size_t size = 0;
    for (const PlyProperty& p : element.properties) size += Cursor::min_bytes(p);
    return size;
}

template <class Cursor>
void skip_property(Cursor& cursor, const PlyProperty& p) {
    if (!p.is_list) {
        cursor.skip_value(p.type);
        return;
    }
    const std::int64_t count = cursor.integer(p.count_type, "list count");
    if (count < 0) cursor.fail("negative list count " + std::to_string(count));
    cursor.skip_items(count, p.type);
}

template <class Cursor>
void skip_element(Cursor& cursor, const PlyElement& element) {
    if (element.properties.empty()) return;  // takes no bytes, however many it claims
    cursor.check_count(element, min_record_size<Cursor>(element));
    for (std::uint64_t i = 0; i < element.count; ++i) {
        for (const PlyProperty& p : element.properties) skip_property(cursor, p);
    }
}

template <class Cursor>
void read_vertices(Cursor& cursor, const PlyElement& element, const VertexLayout& layout, MeshBuilder& builder) {
    cursor.check_count(element, min_record_size<Cursor>(element));
    const auto count = static_cast<std::size_t>(element.count);
    builder.positions.reserve(count);
    if (layout.has_normals()) builder.normals.reserve(count);
    if (layout.has_uvs()) builder.uvs.reserve(count);
    std::vector<double> values(element.properties.size());
    for (std::size_t i = 0; i < count; ++i) {
        for (std::size_t j = 0; j < element.properties.size(); ++j) {
            const PlyProperty& p = element.properties[j];
            if (p.is_list) {
                skip_property(cursor, p);
            } else {
                values[j] = cursor.number(p.type);
            }
        }
        builder.positions.push_back(
            {to_float(values[layout.x]), to_float(values[layout.y]), to_float(values[layout.z])});
        if (layout.has_normals()) {
            builder.normals.push_back(
                {to_float(values[layout.nx]), to_float(values[layout.ny]), to_float(values[layout.nz])});
        }
        if (layout.has_uvs()) builder.uvs.push_back({to_float(values[layout.u]), to_float(values[layout.v])});
    }
}

// Calls on_face(corners) for each face, its vertex indices checked against `vertex_count`.
template <class Cursor, class OnFace>
void read_faces(Cursor& cursor, const PlyElement& element, int list, std::uint64_t vertex_count, OnFace&& on_face) {
    cursor.check_count(element, min_record_size<Cursor>(element));
    std::vector<std::uint32_t> corners;
    for (std::uint64_t f = 0; f < element.count; ++f) {
        for (std::size_t j = 0; j < element.properties.size(); ++j) {
            const PlyProperty& p = element.properties[j];
            if (static_cast<int>(j) != list) {
                skip_property(cursor, p);
                continue;
            }
            const std::int64_t count = cursor.integer(p.count_type, "face corner count");
            if (count < 0) cursor.fail("face " + std::to_string(f) + " has a negative corner count");
            // Checked before resizing: the count is the file's claim.
            if (!cursor.items_fit(count, p.type)) {
                cursor.fail("face " + std::to_string(f) + " claims " + std::to_string(count) +
                            " corners, more than fit before the end of file");
            }
            corners.resize(static_cast<std::size_t>(count));
            for (std::uint32_t& corner : corners) {
                const std::int64_t index = cursor.integer(p.type, "vertex index");
                if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count) {
                    cursor.fail("face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                                " out of range (the file has " + std::to_string(vertex_count) + " vertices)");
                }
                corner = static_cast<std::uint32_t>(index);
            }
        }
        on_face(corners);
    }
}

struct PlyPlan {
    int vertex_element = -1;
    int face_element = -1;
    int face_list = -1;
    VertexLayout layout;
};

PlyPlan plan_elements(const PlyHeader& header, const std::string& where) {
    PlyPlan plan;
    for (std::size_t e = 0; e < header.elements.size(); ++e) {
        const PlyElement& element = header.elements[e];
        if (element.name == "vertex" && plan.vertex_element < 0) plan.vertex_element = static_cast<int>(e);
        if (element.name == "face" && plan.face_element < 0) plan.face_element = static_cast<int>(e);
    }
    if (plan.vertex_element < 0) throw Error(where, "no 'element vertex' in the PLY header");
    const PlyElement& vertex = header.elements[plan.vertex_element];
    const std::string vertex_at = where + ":" + std::to_string(vertex.line);
    // Vertex indices are 32-bit; kNoNormal stays free.
    if (vertex.count >= kNoNormal) {
        throw Error(vertex_at, "more vertices than sombra can index (" + std::to_string(vertex.count) + ")");
    }
    auto scalar = [&](const char* name) {
        const int index = vertex.find(name);
        if (index >= 0 && vertex.properties[index].is_list)
            throw Error(vertex_at, std::string("vertex property ") + name + " is a list");
        return index;
    };
    plan.layout = {scalar("x"), scalar("y"), scalar("z"), scalar("nx"), scalar("ny"), scalar("nz")};
    for (const auto& [u, v] : {std::pair{"u", "v"}, std::pair{"s", "t"}, std::pair{"texture_u", "texture_v"}}) {
        if (plan.layout.has_uvs()) break;
        plan.layout.u = scalar(u);
        plan.layout.v = scalar(v);
    }
    if (plan.layout.x < 0 || plan.layout.y < 0 || plan.layout.z < 0) {
        throw Error(vertex_at, "element vertex lacks one of the properties x, y, z");
    }
    if (plan.face_element >= 0) {
        const PlyElement& face = header.elements[plan.face_element];
        plan.face_list = face.find("vertex_indices");
        if (plan.face_list < 0) plan.face_list = face.find("vertex_index");
        if (plan.face_list < 0 || !face.properties[plan.face_list].is_list) {
            throw Error(where + ":" + std::to_string(face.line),
                        "element face has no list property vertex_indices or vertex_index");
        }
    }
    return plan;
}

template <class Cursor>
void read_body(Cursor& cursor, const PlyHeader& header, const PlyPlan& plan, MeshBuilder& builder) {
    const bool normals = plan.layout.has_normals();
    const bool uvs = plan.layout.has_uvs();
    const std::uint64_t vertex_count = header.elements[plan.vertex_element].count;
    // Polygons are split on their positions, so faces that come before the
    // vertices in the file wait here until the vertices are read.
    bool have_vertices = false;
    std::vector<std::uint32_t> waiting_corners, waiting_sizes;
    auto add_face = [&](std::span<const std::uint32_t> corners) {
        builder.add_face(corners, normals ? corners : std::span<const std::uint32_t>(), kNoMaterial,
                         uvs ? corners : std::span<const std::uint32_t>());
    };
    for (std::size_t e = 0; e < header.elements.size(); ++e) {
        const PlyElement& element = header.elements[e];
        if (static_cast<int>(e) == plan.vertex_element) {
            read_vertices(cursor, element, plan.layout, builder);
            have_vertices = true;
        } else if (static_cast<int>(e) == plan.face_element) {
            // The count is the file's claim: checked against the bytes left before reserving for it.
            cursor.check_count(element, min_record_size<Cursor>(element));
            // A triangle takes at least 4 bytes (a count and three 1-byte indices): empty faces reserve nothing.
            const std::uint64_t most_triangles = cursor.remaining() / 4;
            builder.reserve_triangles(static_cast<std::size_t>(std::min<std::uint64_t>(element.count, most_triangles)));
            read_faces(cursor, element, plan.face_list, vertex_count, [&](const std::vector<std::uint32_t>& corners) {
                if (have_vertices) {
                    add_face(corners);
                    return;
                }
                waiting_corners.insert(waiting_corners.end(), corners.begin(), corners.end());
                waiting_sizes.push_back(static_cast<std::uint32_t>(corners.size()));
            });
        } else {
            skip_element(cursor, element);
        }
    }
    std::size_t offset = 0;
    for (std::uint32_t size : waiting_sizes) {
        add_face(std::span<const std::uint32_t>(waiting_corners).subspan(offset, size));
        offset += size;
    }
}

}  // namespace

LoadedMesh load_ply(const std::filesystem::path& path, Diagnostics& diag) {
    const std::string where = path.string();
    const std::string bytes = read_mesh_file(path);
    const PlyHeader header = parse_ply_header(bytes, where);
    const PlyPlan plan = plan_elements(header, where);

    MeshBuilder builder(where);
    if (header.format == PlyFormat::Ascii) {
        PlyAsciiCursor cursor{bytes.data() + header.body_offset, bytes.data() + bytes.size(), header.body_line, &where};
        read_body(cursor, header, plan, builder);
    } else {
        const auto* begin = reinterpret_cast<const unsigned char*>(bytes.data());
        const bool file_little = header.format == PlyFormat::BinaryLittleEndian;
        const bool swap = file_little != (std::endian::native == std::endian::little);
        PlyBinaryCursor cursor{begin, begin + header.body_offset, begin + bytes.size(), swap, &where};
        read_body(cursor, header, plan, builder);
    }
    return builder.finish({}, diag);
}

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
