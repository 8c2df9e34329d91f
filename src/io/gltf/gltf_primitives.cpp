// A glTF mesh's triangle primitives → PrimitiveData: attributes and
// indices read through the checked accessors (or Draco), the features that
// are skipped counted for the loader's one warning each.
#include "io/gltf/gltf.h"
#include "scene/mesh.h"

namespace sombra::gltf {

namespace {

// A primitive's attributes and indices, read and checked; v flipped.
PrimitiveData read_primitive(const AccessorReader& r, const tinygltf::Primitive& p, const std::string& what) {
    const auto attribute = [&](const char* name) {
        const auto it = p.attributes.find(name);
        return it == p.attributes.end() ? -1 : it->second;
    };
    if (attribute("POSITION") < 0) throw Unsupported{"primitives without POSITION"};
    PrimitiveData out;
    out.material = p.material;
    const std::vector<float> pos = read_floats(r, attribute("POSITION"), Semantic::Position, "POSITION of " + what);
    const std::size_t n = pos.size() / 3;
    if (n >= kNoNormal) throw Error(r.file, what + ": too many vertices");
    out.positions.resize(n);
    for (std::size_t i = 0; i < n; ++i) out.positions[i] = {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]};
    if (attribute("NORMAL") >= 0) {
        const std::vector<float> nor = read_floats(r, attribute("NORMAL"), Semantic::Normal, "NORMAL of " + what);
        if (nor.size() != pos.size()) throw Error(r.file, what + ": NORMAL and POSITION differ in count");
        out.normals.resize(n);
        for (std::size_t i = 0; i < n; ++i) out.normals[i] = {nor[3 * i], nor[3 * i + 1], nor[3 * i + 2]};
    }
    for (unsigned set = 0; set < kUvSets; ++set) {
        const std::string name = texcoord_name(set);
        if (attribute(name.c_str()) < 0) continue;
        const std::vector<float> uv = read_floats(r, attribute(name.c_str()), Semantic::Texcoord, name + " of " + what);
        if (uv.size() / 2 != n) throw Error(r.file, what + ": " + name + " and POSITION differ in count");
        std::vector<Vec2>& uvs = set == 0 ? out.uvs : out.extra_uvs[set - 1];
        uvs.resize(n);
        // glTF's v = 0 is the image's top row; sombra's uvs (like OBJ's) put v = 0 at the bottom.
        for (std::size_t i = 0; i < n; ++i) uvs[i] = {uv[2 * i], 1.0f - uv[2 * i + 1]};
    }
    if (attribute("TANGENT") >= 0) {
        const std::vector<float> t = read_floats(r, attribute("TANGENT"), Semantic::Tangent, "TANGENT of " + what);
        if (t.size() / 4 != n) throw Error(r.file, what + ": TANGENT and POSITION differ in count");
        out.tangents = tangents_of(t);
    }
    if (attribute("COLOR_0") >= 0) {
        const std::vector<float> c = read_floats(r, attribute("COLOR_0"), Semantic::Color, "COLOR_0 of " + what);
        if (c.size() / 4 != n) throw Error(r.file, what + ": COLOR_0 and POSITION differ in count");
        out.colors = colors_of(c, out.clamped_colors);
    }
    if (p.indices >= 0) {
        out.indices = read_indices(r, p.indices, n, "indices of " + what);
    } else {
        out.indices.resize(n);
        for (std::size_t i = 0; i < n; ++i) out.indices[i] = static_cast<std::uint32_t>(i);
    }
    return out;
}

}  // namespace

Primitives read_mesh(const AccessorReader& reader, int index, std::size_t material_count,
                     std::map<std::string, std::size_t>& skipped, std::size_t& clamped_colors) {
    const tinygltf::Mesh& mesh = reader.model.meshes[std::size_t(index)];
    Primitives out(mesh.primitives.size());
    for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
        const tinygltf::Primitive& p = mesh.primitives[i];
        const std::string what = "mesh " + std::to_string(index) + " primitive " + std::to_string(i);
        if (p.mode != TINYGLTF_MODE_TRIANGLES) {
            ++skipped["primitives of mode " + std::to_string(p.mode) + " (only 4, triangles, is drawn)"];
            continue;
        }
        if (p.material < -1 || p.material >= int(material_count))
            throw Error(reader.file, what + " names material " + std::to_string(p.material) + ", but the file has " +
                                         std::to_string(material_count));
        const auto read = [](const std::string& name) {
            for (unsigned set = 0; set < kUvSets; ++set)
                if (name == texcoord_name(set)) return true;
            return name == "COLOR_0";
        };
        for (const auto& [name, accessor] : p.attributes)
            if (name.rfind("TEXCOORD_", 0) == 0 || name.rfind("COLOR_", 0) == 0 || name.rfind("JOINTS_", 0) == 0 ||
                name.rfind("WEIGHTS_", 0) == 0)
                if (!read(name)) ++skipped["attribute " + name + " (not used yet)"];
        if (!p.targets.empty()) ++skipped["morph targets"];
        try {
            const auto draco = p.extensions.find(kDraco);
            out[i] = draco != p.extensions.end() ? decode_draco(reader, p, draco->second, what)
                                                 : read_primitive(reader, p, what);
        } catch (const Unsupported& u) {
            ++skipped[u.feature];
            continue;
        }
        if (out[i]->indices.size() % 3 != 0) ++skipped["trailing indices that make no whole triangle"];
        clamped_colors += out[i]->clamped_colors;
    }
    return out;
}

bool lacks_texcoord(const PrimitiveData& p, const GltfMaterialTextures& refs) {
    for (const GltfTextureRef* ref :
         {&refs.base_color, &refs.metallic_roughness, &refs.normal, &refs.emissive, &refs.occlusion, &refs.specular,
          &refs.specular_color, &refs.transmission, &refs.clearcoat, &refs.clearcoat_roughness})
        if (ref->present() && ref->texcoord >= 1 && ref->texcoord < int(kUvSets) &&
            p.extra_uvs[std::size_t(ref->texcoord) - 1].empty())
            return true;
    return false;
}

}  // namespace sombra::gltf
