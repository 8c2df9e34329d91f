// PLY (ascii, binary little and big endian) → LoadedMesh (spec §9): vertex
// x, y, z (and nx, ny, nz when all three are there), face lists named
// vertex_indices or vertex_index; every other element and property skipped.
// Every count the header claims is checked against the bytes left before
// anything is reserved for it.
#include "io/mesh_file.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/mesh_builder.h"
#include "io/ply/ply_binary_stream.h"
#include "io/ply/ply_format.h"

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

// Is `line` (one header line, without its '\n') the end_header line, by
// parse_ply_header's rule: its first word, between spaces or tabs?
bool is_end_header(std::string_view line) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::size_t begin = line.find_first_not_of(" \t");
    if (begin == std::string_view::npos) return false;
    const std::size_t end = line.find_first_of(" \t", begin);
    return line.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin) == "end_header";
}

// Reads `file` from its start until `bytes` holds the whole header: up to a
// line that ends it (and whatever of the body came in the same reads), or
// the whole file when none does, as parse_ply_header then reports. Stops
// after the first line when that is not "ply": the parser rejects the file there.
void read_ply_start(std::FILE* file, const std::string& where, std::string& bytes) {
    char chunk[1 << 16];
    std::size_t line_start = 0;
    for (int line = 1;;) {
        // Look at every complete line read so far.
        for (std::size_t end; (end = bytes.find('\n', line_start)) != std::string::npos; line_start = end + 1, ++line) {
            const std::string_view text = std::string_view(bytes).substr(line_start, end - line_start);
            if (line == 1 ? text.substr(0, 3) != "ply" : is_end_header(text)) return;
        }
        const std::size_t got = std::fread(chunk, 1, sizeof chunk, file);
        if (got == 0) break;
        bytes.append(chunk, got);
    }
    if (std::ferror(file)) throw Error(where, std::string("cannot read: ") + std::strerror(errno));
}

}  // namespace

LoadedMesh load_ply(const std::filesystem::path& path, Diagnostics& diag) {
    const std::string where = path.string();
    const OpenMeshFile opened = open_mesh_file(path);
    std::string bytes;
    read_ply_start(opened.file.get(), where, bytes);
    const PlyHeader header = parse_ply_header(bytes, where);
    const PlyPlan plan = plan_elements(header, where);

    MeshBuilder builder(where);
    if (header.format == PlyFormat::Ascii) {
        // Ascii bodies are parsed from text: the whole file, as the other text formats.
        read_rest_of_file(opened.file.get(), where, bytes);
        PlyAsciiCursor cursor{bytes.data() + header.body_offset, bytes.data() + bytes.size(), header.body_line, &where};
        read_body(cursor, header, plan, builder);
    } else {
        // Binary bodies are read in slices straight into the mesh's arrays,
        // which are reserved from the header's counts once those are checked
        // against the file's size: no copy of the whole file is held.
        const bool file_little = header.format == PlyFormat::BinaryLittleEndian;
        const bool swap = file_little != (std::endian::native == std::endian::little);
        PlyBinaryStream stream(opened.file.get(), std::string_view(bytes).substr(header.body_offset),
                               header.body_offset, std::max<std::uint64_t>(opened.size_on_disk, bytes.size()), swap,
                               &where);
        std::string().swap(bytes);
        read_body(stream, header, plan, builder);
    }
    return builder.finish({}, diag);
}

}  // namespace sombra
