// OBJ (+MTL) → LoadedMesh (spec §5, §9). sombra's own parser (obj_parse.h)
// reads the geometry; tinyobjloader's LoadMtl reads the MTL files it names
// (obj_material.h); PolygonMeshBuilder splits polygons and drops what would
// poison the renderer. tinyobjloader's LoadObj was replaced because parsing
// was most of a run's time (docs/performance.md, "OBJ parser").
#include <tiny_obj_loader.h>

#include <cctype>
#include <map>
#include <set>
#include <string_view>
#include <unordered_map>

#include "scene/mesh_file.h"
#include "scene/obj_material.h"
#include "scene/obj_parse.h"
#include "scene/polygon_file.h"
#include "scene/polygon_mesh_builder.h"

namespace sombra {
namespace {

std::string_view trim(std::string_view s) {
    const auto blank = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
    while (!s.empty() && blank(s.front())) s.remove_prefix(1);
    while (!s.empty() && blank(s.back())) s.remove_suffix(1);
    return s;
}

// Forwards warnings, one per line of `text`, identical ones merged and the
// total capped so that a hostile file cannot flood the terminal.
void forward_warnings(const std::string& where, const std::string& text, Diagnostics& diag) {
    constexpr std::size_t kMaxDistinct = 20;
    std::vector<std::pair<std::string, std::size_t>> messages;
    std::unordered_map<std::string, std::size_t> index_of;
    std::size_t begin = 0;
    while (begin < text.size()) {
        std::size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        std::string_view line = trim(std::string_view(text).substr(begin, end - begin));
        // tinyobjloader ends some messages with "\n.", which lands in front of the next one.
        while (line.starts_with('.')) line = trim(line.substr(1));
        begin = end + 1;
        if (line.empty()) continue;
        const auto [it, added] = index_of.emplace(std::string(line), messages.size());
        if (added) messages.emplace_back(std::string(line), 0);
        ++messages[it->second].second;
    }
    for (std::size_t i = 0; i < messages.size() && i < kMaxDistinct; ++i) {
        const auto& [line, count] = messages[i];
        diag.warn(where, count > 1 ? line + " (" + std::to_string(count) + " times)" : line);
    }
    if (messages.size() > kMaxDistinct) {
        diag.warn(where, std::to_string(messages.size() - kMaxDistinct) + " more warnings like these not shown");
    }
}

// The file names of an `mtllib` line as tinyobjloader splits them: at
// spaces, a backslash keeping the next character (so "a\ b.mtl" is one name).
std::vector<std::string> mtllib_names(std::string_view text) {
    std::vector<std::string> names;
    std::string name;
    bool escaping = false;
    for (char c : text) {
        if (escaping) {
            escaping = false;
        } else if (c == '\\') {
            escaping = true;
            continue;
        } else if (c == ' ') {
            if (!name.empty()) names.push_back(name);
            name.clear();
            continue;
        }
        name += c;
    }
    names.push_back(name);  // the last one even when empty, as tinyobjloader does
    return names;
}

// The MTL side of an OBJ: files read so far, their materials, the current `usemtl`.
struct ObjMaterials {
    explicit ObjMaterials(const std::filesystem::path& folder) : reader(folder) {}

    MtlBesideObj reader;
    std::vector<tinyobj::material_t> materials;
    std::map<std::string, int> index_of;
    std::set<std::string> files_read;
    int current = -1;
    std::string notes;  // warnings, one a line

    // `mtllib`: the first of its files that can be read (tinyobjloader's rule).
    void read_library(std::string_view text) {
        bool found = false;
        for (const std::string& name : mtllib_names(text)) {
            if (files_read.count(name) > 0) {
                found = true;
                continue;
            }
            std::string warn, err;
            const bool ok = reader(name, &materials, &index_of, &warn, &err);
            notes += warn + "\n" + err + "\n";
            if (ok) {
                found = true;
                files_read.insert(name);
                break;
            }
        }
        if (!found) notes += "mtllib " + std::string(text) + ": no material file read; its materials are unknown\n";
    }

    void use(std::string_view name) {
        const auto it = index_of.find(std::string(name));
        current = it != index_of.end() ? it->second : -1;
        if (it == index_of.end()) notes += "unknown material '" + std::string(name) + "' (usemtl): its faces get the default material\n";
    }

    std::uint32_t current_id() const {
        return current >= 0 && std::size_t(current) < materials.size() ? static_cast<std::uint32_t>(current)
                                                                         : kNoMaterial;
    }
};

}  // namespace

LoadedMesh load_obj(const std::filesystem::path& path, Diagnostics& diag) {
    const std::string where = path.string();
    const std::string bytes = read_polygon_file(path);
    std::string_view text = bytes;
    if (text.starts_with("\xFE\xFF") || text.starts_with("\xFF\xFE")) {
        throw Error(where, "no triangles: the file is UTF-16 text; save it as UTF-8 or ASCII");
    }
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 byte order mark
    ObjGeometry geometry = parse_obj(text, where);

    PolygonMeshBuilder builder(where);
    builder.skipped_small_faces = geometry.small_faces;
    builder.positions = std::move(geometry.positions);
    builder.normals = std::move(geometry.normals);
    std::size_t triangle_estimate = 0;
    for (const ObjFaceBlock& block : geometry.faces) {
        triangle_estimate += block.positions.size() - 2 * block.ends.size();
    }
    builder.reserve_triangles(triangle_estimate);

    ObjMaterials mtl(path.parent_path());
    auto directive = geometry.directives.cbegin();
    // Applies the `usemtl` and `mtllib` lines before the face-th face, in file order.
    auto apply_directives_before = [&](std::size_t face) {
        for (; directive != geometry.directives.cend() && directive->face <= face; ++directive) {
            if (directive->kind == ObjDirective::Kind::Usemtl) mtl.use(directive->text);
            else mtl.read_library(directive->text);
        }
    };
    std::size_t face = 0;
    for (const ObjFaceBlock& block : geometry.faces) {
        std::uint32_t begin = 0;
        for (const std::uint32_t end : block.ends) {
            apply_directives_before(face++);
            const std::span<const std::uint32_t> positions(block.positions.data() + begin, end - begin);
            std::span<const std::uint32_t> normals(block.normals.data() + begin, end - begin);
            bool any_normal = false;
            for (std::uint32_t n : normals) any_normal |= n != kNoNormal;
            builder.add_face(positions, any_normal ? normals : std::span<const std::uint32_t>(), mtl.current_id());
            begin = end;
        }
    }
    apply_directives_before(std::numeric_limits<std::size_t>::max());
    forward_warnings(where, mtl.notes, diag);
    if (geometry.bad_normal_refs > 0) {
        diag.warn(where, std::to_string(geometry.bad_normal_refs) +
                             " face corners refer to normals the file does not define: those corners have none");
    }

    std::vector<Material> materials;
    materials.reserve(mtl.materials.size() + 1);
    for (std::size_t i = 0; i < mtl.materials.size(); ++i) {
        materials.push_back(material_from_mtl(mtl.materials[i], mtl.reader.source(i, where), diag));
    }
    return builder.finish(std::move(materials), diag);
}

}  // namespace sombra
