#include "scene/obj_material.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "core/format.h"

namespace sombra {
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
    std::ifstream in;
    if (std::filesystem::is_regular_file(path, ec)) in.open(path);
    if (!in.is_open()) {
        if (warn) *warn += "material file '" + name + "' not found beside the OBJ (" + path.string() + ")\n";
        return false;
    }
    tinyobj::LoadMtl(name_to_index, materials, &in, warn, err);
    sources_.resize(materials->size(), path.string());
    return true;
}

Material material_from_mtl(const tinyobj::material_t& mtl, const std::string& where, Diagnostics& diag) {
    Material m;
    m.name = mtl.name;
    m.kd = clamp_rgb(mtl.diffuse, 1, "Kd", mtl, where, diag);
    const Vec3 ks = clamp_rgb(mtl.specular, 1, "Ks", mtl, where, diag);
    // Emission is a radiance: unbounded above, but it must stay finite.
    m.ke = clamp_rgb(mtl.emission, std::numeric_limits<float>::infinity(), "Ke", mtl, where, diag);
    if (max_component(ks) > 0) {
        m.type = MaterialType::Phong;
        m.ks = ks;
        const float ns = static_cast<float>(mtl.shininess);
        m.shininess = std::isnan(ns) ? 1.0f : std::clamp(ns, 0.0f, kMaxMtlShininess);
        if (!(m.shininess == ns)) {
            diag.warn(where, "material '" + mtl.name + "': Ns " + format_number(mtl.shininess) + " clamped to [0, " +
                                 format_number(kMaxMtlShininess) + "]");
        }
        if (breaks_energy_conservation(m))
            diag.warn(where, "material '" + mtl.name +
                                 "': Kd + Ks exceeds 1 in some channel: the material reflects more light than it receives");
    }
    return m;
}

}  // namespace sombra
