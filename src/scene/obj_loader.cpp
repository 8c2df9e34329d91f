// OBJ (+MTL) → LoadedMesh (spec §5, §9). tinyobjloader parses the text, with
// its own triangulation off; sombra then does what tinyobjloader leaves to
// its caller: checking every index, splitting polygons, catching nan/inf
// coordinates, and mapping MTL parameters to materials.
#include <tiny_obj_loader.h>

#include <cctype>
#include <cmath>
#include <istream>
#include <limits>
#include <streambuf>
#include <string_view>
#include <unordered_map>

#include "scene/mesh_file.h"
#include "scene/obj_material.h"
#include "scene/obj_scan.h"
#include "scene/polygon_file.h"
#include "scene/polygon_mesh_builder.h"

namespace sombra {
namespace {

// Lets tinyobjloader read the bytes already in memory.
struct MemoryStreamBuf : std::streambuf {
    MemoryStreamBuf(const char* begin, const char* end) {
        char* first = const_cast<char*>(begin);  // read-only use: only the get area is set
        setg(first, first, const_cast<char*>(end));
    }
};

std::string_view trim(std::string_view s) {
    const auto blank = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
    while (!s.empty() && blank(s.front())) s.remove_prefix(1);
    while (!s.empty() && blank(s.back())) s.remove_suffix(1);
    return s;
}

// Calls line(text) for each trimmed, non-empty line of tinyobjloader's message text.
template <class Line>
void for_each_message_line(const std::string& text, Line&& line) {
    std::size_t begin = 0;
    while (begin < text.size()) {
        std::size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        std::string_view piece = trim(std::string_view(text).substr(begin, end - begin));
        // tinyobjloader ends some messages with "\n.", which lands in front of the next one.
        while (piece.starts_with('.')) piece = trim(piece.substr(1));
        if (!piece.empty()) line(piece);
        begin = end + 1;
    }
}

// tinyobjloader's parse error as one line; its "line N" also goes into WHERE.
Error parse_error(const std::string& where, const std::string& err) {
    std::string what;
    for_each_message_line(err, [&](std::string_view piece) {
        if (!what.empty()) what += "; ";
        what += piece;
    });
    if (what.empty()) what = "cannot be parsed";
    what[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(what[0])));
    for (std::size_t at = what.find("line "); at != std::string::npos; at = what.find("line ", at + 1)) {
        std::size_t digits = at + 5;
        while (digits < what.size() && std::isdigit(static_cast<unsigned char>(what[digits]))) ++digits;
        if (digits > at + 5) return Error(where + ":" + what.substr(at + 5, digits - at - 5), what);
    }
    return Error(where, what);
}

// Forwards tinyobjloader's warnings, identical ones merged and the total capped
// so that a hostile file cannot flood the terminal. Returns how many faces it
// dropped for having fewer than 3 corners ("Degenerated face found").
std::size_t forward_warnings(const std::string& where, const std::string& text, Diagnostics& diag) {
    constexpr std::size_t kMaxDistinct = 20;
    std::size_t small_faces = 0;
    std::vector<std::pair<std::string, std::size_t>> messages;
    std::unordered_map<std::string, std::size_t> index_of;
    for_each_message_line(text, [&](std::string_view line) {
        if (line.starts_with("Degenerated face found")) {
            ++small_faces;
            return;
        }
        // Index ranges are checked here, per face, with better messages.
        if (line.starts_with("Vertex") && line.find("indices out of bounds") != std::string_view::npos) return;
        const auto [it, added] = index_of.emplace(std::string(line), messages.size());
        if (added) messages.emplace_back(std::string(line), 0);
        ++messages[it->second].second;
    });
    for (std::size_t i = 0; i < messages.size() && i < kMaxDistinct; ++i) {
        const auto& [line, count] = messages[i];
        diag.warn(where, count > 1 ? line + " (" + std::to_string(count) + " times)" : line);
    }
    if (messages.size() > kMaxDistinct) {
        diag.warn(where, std::to_string(messages.size() - kMaxDistinct) + " more tinyobjloader warnings not shown");
    }
    return small_faces;
}

// Corner counts of every face, in shape order. tinyobjloader stores them in a
// byte; when a polygon has more than 255 corners the stored counts no longer
// add up, and the true ones are read from the text.
std::vector<std::uint32_t> face_sizes(const std::vector<tinyobj::shape_t>& shapes, std::string_view text,
                                      const std::string& where) {
    std::vector<std::uint32_t> sizes;
    bool consistent = true;
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t corners = 0;
        for (unsigned char n : shape.mesh.num_face_vertices) {
            sizes.push_back(n);
            corners += n;
        }
        consistent &= corners == shape.mesh.indices.size();
    }
    if (consistent) return sizes;

    const std::vector<ObjFaceLine> lines = scan_obj_faces(text);
    bool matches = lines.size() == sizes.size();
    for (std::size_t f = 0; matches && f < sizes.size(); ++f) {
        matches = lines[f].corners % 256 == sizes[f];
        sizes[f] = lines[f].corners;
    }
    std::size_t f = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t corners = 0;
        for (std::size_t k = 0; matches && k < shape.mesh.num_face_vertices.size(); ++k) corners += sizes[f++];
        matches &= corners == shape.mesh.indices.size();
    }
    if (!matches) throw Error(where, "cannot match the corners of a polygon with more than 255 corners to its face");
    return sizes;
}

}  // namespace

LoadedMesh load_obj(const std::filesystem::path& path, Diagnostics& diag) {
    const std::string where = path.string();
    std::string bytes = read_polygon_file(path);
    std::string_view text = bytes;
    if (text.starts_with("\xFE\xFF") || text.starts_with("\xFF\xFE")) {
        throw Error(where, "no triangles: the file is UTF-16 text; save it as UTF-8 or ASCII");
    }
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 byte order mark
    comment_out_skin_weights(std::span<char>(bytes).subspan(bytes.size() - text.size()));
    // tinyobjloader wraps huge indices into valid ones and reports a 0 without saying which.
    if (const auto bad = find_bad_face_index(text)) throw Error(where + ":" + std::to_string(bad->line), bad->what);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> mtl_materials;
    std::string warn, err;
    MtlBesideObj mtl_reader(path.parent_path());
    MemoryStreamBuf buffer(text.data(), text.data() + text.size());
    std::istream stream(&buffer);
    if (!tinyobj::LoadObj(&attrib, &shapes, &mtl_materials, &warn, &err, &stream, &mtl_reader,
                          /*triangulate=*/false, /*default_vcols_fallback=*/false)) {
        throw parse_error(where, err);
    }

    PolygonMeshBuilder builder(where);
    builder.skipped_small_faces = forward_warnings(where, warn, diag);
    forward_warnings(where, err, diag);  // errors tinyobjloader survived (in an MTL file, say)

    const std::size_t vertex_count = attrib.vertices.size() / 3;
    builder.positions.resize(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
        builder.positions[i] = {attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]};
    }
    for (std::uint32_t i : find_non_finite_vertices(text)) {
        if (i < vertex_count) builder.positions[i] = Vec3(std::numeric_limits<float>::quiet_NaN());
    }
    const std::size_t normal_count = attrib.normals.size() / 3;
    builder.normals.resize(normal_count);
    for (std::size_t i = 0; i < normal_count; ++i) {
        builder.normals[i] = {attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]};
    }

    const std::vector<std::uint32_t> sizes = face_sizes(shapes, text, where);
    std::size_t triangle_estimate = 0;
    for (std::uint32_t n : sizes) triangle_estimate += n >= 3 ? n - 2 : 0;
    builder.reserve_triangles(triangle_estimate);

    // WHERE of the face-th face: its line, found only when needed.
    auto face_where = [&](std::size_t face) {
        const std::vector<ObjFaceLine> lines = scan_obj_faces(text);
        return face < lines.size() ? where + ":" + std::to_string(lines[face].line) : where;
    };
    std::vector<std::uint32_t> position_corners, normal_corners;
    std::size_t face = 0, bad_normal_refs = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
            const std::uint32_t n = sizes[face];
            position_corners.clear();
            normal_corners.clear();
            bool any_normal = false;
            for (std::size_t k = offset; k < offset + n; ++k) {
                const tinyobj::index_t& corner = shape.mesh.indices[k];
                if (corner.vertex_index < 0 || std::size_t(corner.vertex_index) >= vertex_count) {
                    throw Error(face_where(face), "face index " + std::to_string(corner.vertex_index + 1LL) +
                                                      " out of range (the file has " + std::to_string(vertex_count) +
                                                      " vertices)");
                }
                position_corners.push_back(static_cast<std::uint32_t>(corner.vertex_index));
                std::uint32_t normal = kNoNormal;
                if (corner.normal_index >= 0 && std::size_t(corner.normal_index) < normal_count) {
                    normal = static_cast<std::uint32_t>(corner.normal_index);
                    any_normal = true;
                } else if (corner.normal_index != -1) {
                    ++bad_normal_refs;
                }
                normal_corners.push_back(normal);
            }
            offset += n;
            const int id = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            const std::uint32_t material =
                id >= 0 && std::size_t(id) < mtl_materials.size() ? static_cast<std::uint32_t>(id) : kNoMaterial;
            builder.add_face(position_corners, any_normal ? std::span(normal_corners) : std::span<std::uint32_t>(),
                             material);
        }
    }
    if (bad_normal_refs > 0) {
        diag.warn(where, std::to_string(bad_normal_refs) +
                             " face corners refer to normals the file does not define: those corners have none");
    }

    std::vector<Material> materials;
    materials.reserve(mtl_materials.size() + 1);
    for (std::size_t i = 0; i < mtl_materials.size(); ++i) {
        materials.push_back(material_from_mtl(mtl_materials[i], mtl_reader.source(i, where), diag));
    }
    return builder.finish(std::move(materials), diag);
}

}  // namespace sombra
