// OBJ (+MTL) → LoadedMesh (spec §5, §9, §11). sombra's own parser (obj_parse.h)
// reads the geometry; tinyobjloader's LoadMtl reads the MTL files it names
// (MtlBesideObj below), whose parameters become sombra's diffuse, Phong,
// mirror, dielectric and pbr materials; MeshBuilder (mesh_builder.h) splits polygons and drops what would
// poison the renderer. The geometry has its own parser because tinyobjloader's
// LoadObj is slow enough to dominate a run on large models.
#include "io/mesh_file.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "io/mesh_builder.h"
#include "io/obj/mtl_scan.h"
#include "io/obj/mtl_textures.h"
#include "io/obj/obj_parse.h"
#include "scene/material.h"

namespace sombra {

// Opens the files named by `mtllib` relative to the OBJ's folder and records
// which file each material came from. A missing file is a warning (in
// tinyobjloader's warning text); its materials are then unknown names.
class MtlBesideObj final : public tinyobj::MaterialReader {
public:
    explicit MtlBesideObj(std::filesystem::path obj_folder) : folder_(std::move(obj_folder)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* name_to_index, std::string* warn, std::string* err) override;

    // The MTL path material i came from, as a WHERE for messages; `fallback` if unknown.
    const std::string& source(std::size_t i, const std::string& fallback) const {
        return i < sources_.size() ? sources_[i] : fallback;
    }

    // Which of Pr and Pm material i states (tinyobjloader reads their values
    // but not whether they were there); neither if unknown.
    MtlPbrKeys pbr_keys(std::size_t i) const { return i < pbr_keys_.size() ? pbr_keys_[i] : MtlPbrKeys{}; }

private:
    std::filesystem::path folder_;
    std::vector<std::string> sources_;
    std::vector<MtlPbrKeys> pbr_keys_;
};

// illum 5 → mirror with kr = Ks; illum 7 → dielectric with ior = Ni (1.5
// when Ni is missing or <= 1) and kt = Tf (1 when Tf is missing, which
// tinyobjloader reports as 0 0 0); else Pr or Pm → pbr (below); otherwise Kd → kd; Ks > 0 in any channel
// → Phong with ks and shininess Ns, else diffuse (spec §5, §11). Ke → ke.
// Colours are clamped to [0, 1] (Ke only to >= 0, it is a radiance) and Ns
// to [0, kMaxMtlShininess], each with a warning at `where`.
//
// `Pr` or `Pm` (the PBR extension; `pbr` says which were given) → pbr with
// base_color = Kd, roughness = Pr and metallic = Pm, a missing one 0 (what
// tinyobjloader gives, spec §9), each clamped to [0, 1] with a warning, and
// ior = Ni (1.5 when Ni is missing or <= 1).
Material material_from_mtl(const tinyobj::material_t& mtl, MtlPbrKeys pbr, const std::string& where, Diagnostics& diag);

inline constexpr float kMaxMtlShininess = 1e6f;

namespace {

std::string format_rgb(const tinyobj::real_t c[3]) {
    return format_number(c[0]) + " " + format_number(c[1]) + " " + format_number(c[2]);
}

// Clamps each channel to [0, hi]; NaN (and, for an unbounded `hi`, infinity)
// becomes 0. Warns once when anything changed.
Vec3 clamp_rgb(const tinyobj::real_t c[3], float hi, const char* key, const tinyobj::material_t& mtl,
               const std::string& where, Diagnostics& diag) {
    Vec3 out;
    bool changed = false;
    for (int k = 0; k < 3; ++k) {
        const float value = static_cast<float>(c[k]);
        float clamped = std::clamp(value, 0.0f, hi);
        if (std::isnan(value) || std::isinf(clamped)) clamped = 0;  // not a colour, not a radiance
        changed |= !(clamped == value);
        out[k] = clamped;
    }
    if (changed) {
        const std::string range = std::isinf(hi) ? "finite values >= 0" : "[0, 1]";
        diag.warn(where, "material '" + mtl.name + "': " + key + " " + format_rgb(c) + " clamped to " + range);
    }
    return out;
}

}  // namespace

bool MtlBesideObj::operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                              std::map<std::string, int>* name_to_index, std::string* warn, std::string* err) {
    const std::filesystem::path path = folder_ / name;
    std::error_code ec;
    // Only regular files: a folder or a device named by mtllib must not block or fail oddly.
    std::ifstream file;
    if (std::filesystem::is_regular_file(path, ec)) file.open(path, std::ios::binary);
    if (!file.is_open()) {
        if (warn) *warn += "material file '" + name + "' not found beside the OBJ (" + path.string() + ")\n";
        return false;
    }
    std::ostringstream text;
    text << file.rdbuf();
    const std::string mtl_text = std::move(text).str();
    std::istringstream in(mtl_text);
    const std::size_t first = materials->size();
    tinyobj::LoadMtl(name_to_index, materials, &in, warn, err);
    sources_.resize(materials->size(), path.string());
    std::vector<MtlPbrKeys> keys = scan_mtl_pbr_keys(mtl_text);
    // The scan follows LoadMtl's rules; should they ever disagree, no material is taken for pbr.
    if (keys.size() != materials->size() - first) keys.assign(materials->size() - first, MtlPbrKeys{});
    pbr_keys_.resize(first, MtlPbrKeys{});
    pbr_keys_.insert(pbr_keys_.end(), keys.begin(), keys.end());
    return true;
}

namespace {

// An MTL scalar clamped to [0, 1] (NaN becomes 0), with a warning when it changed.
float clamp_unit(tinyobj::real_t value, const char* key, const tinyobj::material_t& mtl, const std::string& where,
                 Diagnostics& diag) {
    const float v = static_cast<float>(value);
    const float clamped = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    if (!(clamped == v))
        diag.warn(where, "material '" + mtl.name + "': " + key + " " + format_number(value) + " clamped to [0, 1]");
    return clamped;
}

}  // namespace

Material material_from_mtl(const tinyobj::material_t& mtl, MtlPbrKeys pbr, const std::string& where,
                           Diagnostics& diag) {
    Material m;
    m.name = mtl.name;
    m.kd = clamp_rgb(mtl.diffuse, 1, "Kd", mtl, where, diag);
    const Vec3 ks = clamp_rgb(mtl.specular, 1, "Ks", mtl, where, diag);
    // Emission is a radiance: unbounded above, but it must stay finite.
    m.ke = clamp_rgb(mtl.emission, std::numeric_limits<float>::infinity(), "Ke", mtl, where, diag);
    if (mtl.illum == 5) {
        m.type = MaterialType::Mirror;
        m.kr = ks;
    } else if (mtl.illum == 7) {
        m.type = MaterialType::Dielectric;
        const float ni = static_cast<float>(mtl.ior);
        m.ior = ni > 1 && std::isfinite(ni) ? ni : 1.5f;
        const Vec3 tf = clamp_rgb(mtl.transmittance, 1, "Tf", mtl, where, diag);
        m.kt = max_component(tf) > 0 ? tf : Vec3{1.0f};
    } else if (pbr.roughness || pbr.metallic) {
        m.type = MaterialType::Pbr;
        m.base_color = m.kd;
        m.roughness = clamp_unit(mtl.roughness, "Pr", mtl, where, diag);
        m.metallic = clamp_unit(mtl.metallic, "Pm", mtl, where, diag);
        const float ni = static_cast<float>(mtl.ior);
        m.ior = ni > 1 && std::isfinite(ni) ? ni : 1.5f;
    } else if (max_component(ks) > 0 || !mtl.specular_texname.empty()) {  // map_Ks: textured Phong (mtl_textures.h)
        m.type = MaterialType::Phong;
        m.ks = ks;
        const float ns = static_cast<float>(mtl.shininess);
        m.shininess = std::isnan(ns) ? 1.0f : std::clamp(ns, 0.0f, kMaxMtlShininess);
        if (!(m.shininess == ns)) {
            diag.warn(where, "material '" + mtl.name + "': Ns " + format_number(mtl.shininess) + " clamped to [0, " +
                                 format_number(kMaxMtlShininess) + "]");
        }
        if (breaks_energy_conservation(m))
            diag.warn(where,
                      "material '" + mtl.name +
                          "': Kd + Ks exceeds 1 in some channel: the material reflects more light than it receives");
    }
    return m;
}

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
        if (it == index_of.end())
            notes += "unknown material '" + std::string(name) + "' (usemtl): its faces get the default material\n";
    }

    std::uint32_t current_id() const {
        return current >= 0 && std::size_t(current) < materials.size() ? static_cast<std::uint32_t>(current)
                                                                       : kNoMaterial;
    }
};

}  // namespace

LoadedMesh load_obj(const std::filesystem::path& path, Diagnostics& diag) {
    const std::string where = path.string();
    const std::string bytes = read_mesh_file(path);
    std::string_view text = bytes;
    if (text.starts_with("\xFE\xFF") || text.starts_with("\xFF\xFE")) {
        throw Error(where, "no triangles: the file is UTF-16 text; save it as UTF-8 or ASCII");
    }
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 byte order mark
    ObjGeometry geometry = parse_obj(text, where);

    MeshBuilder builder(where);
    builder.skipped_small_faces = geometry.small_faces;
    builder.positions = std::move(geometry.positions);
    builder.normals = std::move(geometry.normals);
    builder.uvs = std::move(geometry.texcoords);
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
            if (directive->kind == ObjDirective::Kind::Usemtl)
                mtl.use(directive->text);
            else
                mtl.read_library(directive->text);
        }
    };
    std::size_t face = 0;
    for (const ObjFaceBlock& block : geometry.faces) {
        std::uint32_t begin = 0;
        for (const std::uint32_t end : block.ends) {
            apply_directives_before(face++);
            const std::span<const std::uint32_t> positions(block.positions.data() + begin, end - begin);
            std::span<const std::uint32_t> normals(block.normals.data() + begin, end - begin);
            bool any_normal = false, any_uv = false;
            for (std::uint32_t n : normals) any_normal |= n != kNoNormal;
            std::span<const std::uint32_t> uvs;
            if (!block.texcoords.empty()) uvs = {block.texcoords.data() + begin, end - begin};
            for (std::uint32_t t : uvs) any_uv |= t != kNoUv;
            builder.add_face(positions, any_normal ? normals : std::span<const std::uint32_t>(), mtl.current_id(),
                             any_uv ? uvs : std::span<const std::uint32_t>());
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
    std::vector<Texture> textures;
    MtlTextureReader texture_reader(textures, diag);
    materials.reserve(mtl.materials.size() + 1);
    for (std::size_t i = 0; i < mtl.materials.size(); ++i) {
        const std::string& source = mtl.reader.source(i, where);
        materials.push_back(material_from_mtl(mtl.materials[i], mtl.reader.pbr_keys(i), source, diag));
        texture_reader.apply(mtl.materials[i], source, materials.back());
    }
    LoadedMesh loaded = builder.finish(std::move(materials), diag);
    loaded.textures = std::move(textures);
    return loaded;
}

}  // namespace sombra
