// The "materials" section of a scene file: the types of spec §5 and §11, each
// with its own required keys, defaults and ranges.
#include <algorithm>
#include <cmath>

#include "io/scene_json/scene_json.h"

namespace sombra {
namespace {

// The keys each type accepts; anything else is an error (a typo, or a key of another type).
struct TypeKeys {
    const char* type;
    std::initializer_list<std::string_view> keys;
};
const TypeKeys kTypes[] = {
    {"diffuse", {"type", "kd", "ke", "normal_map", "alpha"}},
    {"phong", {"type", "kd", "ks", "shininess", "ke", "normal_map", "alpha"}},
    {"mirror", {"type", "kr", "ke", "normal_map", "alpha"}},
    {"dielectric", {"type", "ior", "kt", "roughness", "ke", "normal_map", "alpha"}},
    {"conductor", {"type", "ks", "roughness", "ke", "normal_map", "alpha"}},
    {"pbr", {"type", "base_color", "metallic", "roughness", "ior", "ke", "normal_map", "alpha"}},
};
constexpr const char* kTypeList = "'diffuse', 'phong', 'mirror', 'dielectric', 'conductor' or 'pbr'";

// The keys of another type that `type` does not take: "'ks' applies only to
// phong and conductor materials" says more than "unknown key".
void reject_foreign_keys(const SceneJson& s, const Json& v, std::string_view pointer, const TypeKeys& type) {
    for (const auto& [key, value] : v.items()) {
        if (std::find(type.keys.begin(), type.keys.end(), key) != type.keys.end()) continue;
        std::string owners;
        for (const TypeKeys& other : kTypes)
            if (std::find(other.keys.begin(), other.keys.end(), key) != other.keys.end())
                owners += (owners.empty() ? "" : " and ") + std::string(other.type);
        if (owners.empty()) json_fail(s, json_child(pointer, key), "unknown key '" + key + "'");
        json_fail(s, json_child(pointer, key),
                  "'" + key + "' applies only to " + owners + " materials, not " + type.type);
    }
}

void read_phong(const SceneJson& s, const Json& v, std::string_view pointer, Material& m, SceneTextures& textures) {
    read_texturable(s, v, pointer, "ks", true, m, textures);
    const std::string p = json_child(pointer, "shininess");
    m.shininess = read_float(s, require_member(s, v, pointer, "shininess"), p);
    if (m.shininess < 0) json_fail(s, p, "shininess must be non-negative");
    if (breaks_energy_conservation(m) && !m.textures.kd.is_set() && !m.textures.ks.is_set())
        json_warn(s, pointer, "kd + ks exceeds 1 in some channel: the material reflects more light than it receives");
}

// `ior` when given (the default stays 1.5): greater than 1, the outside being vacuum.
void read_optional_ior(const SceneJson& s, const Json& v, std::string_view pointer, Material& m) {
    if (const Json* ior = find_member(v, "ior")) {
        const std::string p = json_child(pointer, "ior");
        m.ior = read_float(s, *ior, p);
        if (!(m.ior > 1)) json_fail(s, p, "ior must be greater than 1 (the outside is vacuum, ior 1)");
    }
}

// A rough dielectric (roughness > 0 or textured, spec §26) is glTF's rough
// transmission through a volume: a pbr material of base colour kt, fully
// transmissive, with GGX refraction (render/bsdf/bsdf_pbr.cpp). Roughness 0
// keeps the smooth glass of §11.
void read_dielectric(const SceneJson& s, const Json& v, std::string_view pointer, Material& m,
                     SceneTextures& textures) {
    read_optional_ior(s, v, pointer, m);
    read_texturable(s, v, pointer, "kt", false, m, textures);
    read_texturable(s, v, pointer, "roughness", false, m, textures);
    if (!(m.roughness > 0.0f) && !m.textures.roughness.is_set()) return;
    m.type = MaterialType::Pbr;
    m.base_color = m.kt;
    m.textures.base_color = m.textures.kt;
    m.textures.kt = TextureRef{};
    m.metallic = 0.0f;
    m.transmission = 1.0f;
    m.thickness = 1.0f;  // bounds a volume: refraction rather than a thin wall
}

void read_conductor(const SceneJson& s, const Json& v, std::string_view pointer, Material& m, SceneTextures& textures) {
    read_texturable(s, v, pointer, "ks", true, m, textures);
    read_texturable(s, v, pointer, "roughness", true, m, textures);
}

// The glTF metallic–roughness material (§11): all but ior required.
void read_pbr(const SceneJson& s, const Json& v, std::string_view pointer, Material& m, SceneTextures& textures) {
    read_texturable(s, v, pointer, "base_color", true, m, textures);
    read_texturable(s, v, pointer, "metallic", true, m, textures);
    read_texturable(s, v, pointer, "roughness", true, m, textures);
    read_optional_ior(s, v, pointer, m);
}

Material read_material(const SceneJson& s, const std::string& name, const Json& v, std::string_view pointer,
                       SceneTextures& textures) {
    expect_object(s, v, pointer);
    const std::string type_pointer = json_child(pointer, "type");
    const std::string& type = read_string(s, require_member(s, v, pointer, "type"), type_pointer);
    const TypeKeys* keys = nullptr;
    for (const TypeKeys& t : kTypes)
        if (type == t.type) keys = &t;
    if (!keys) json_fail(s, type_pointer, "unknown material type '" + type + "' (expected " + kTypeList + ")");
    reject_foreign_keys(s, v, pointer, *keys);

    if (name == "interface")
        json_fail(s, pointer, "'interface' is reserved: it names the boundary rays cross unchanged (spec §26)");
    Material m;
    m.name = name;
    if (type == "diffuse") {
        m.type = MaterialType::Diffuse;
        read_texturable(s, v, pointer, "kd", true, m, textures);
    } else if (type == "phong") {
        m.type = MaterialType::Phong;
        read_texturable(s, v, pointer, "kd", true, m, textures);
        read_phong(s, v, pointer, m, textures);
    } else if (type == "mirror") {
        m.type = MaterialType::Mirror;
        read_texturable(s, v, pointer, "kr", true, m, textures);
    } else if (type == "dielectric") {
        m.type = MaterialType::Dielectric;
        read_dielectric(s, v, pointer, m, textures);
    } else if (type == "conductor") {
        m.type = MaterialType::Conductor;
        read_conductor(s, v, pointer, m, textures);
    } else {
        m.type = MaterialType::Pbr;
        read_pbr(s, v, pointer, m, textures);
    }
    read_texturable(s, v, pointer, "ke", false, m, textures);
    read_material_maps(s, v, pointer, m, textures);
    return m;
}

}  // namespace

std::vector<Material> read_materials(const SceneJson& s, const Json& v, std::string_view pointer,
                                     SceneTextures& textures) {
    expect_object(s, v, pointer);
    std::vector<Material> materials;
    materials.reserve(v.size());
    for (auto it = v.begin(); it != v.end(); ++it)
        materials.push_back(read_material(s, it.key(), it.value(), json_child(pointer, it.key()), textures));
    return materials;
}

}  // namespace sombra
