// The scene file's "media" (spec §26): named participating media, checked
// key by key. Homogeneous media only in this version of sombra; a grid
// (OpenVDB) medium is refused in one line until it is built.
#include <cmath>
#include <string>
#include <vector>

#include "io/scene_json/scene_json.h"

namespace sombra {

namespace {

Medium read_medium(const SceneJson& s, const Json& v, std::string_view pointer, const std::string& name) {
    expect_object(s, v, pointer);
    const std::string type_pointer = json_child(pointer, "type");
    const std::string& type = read_string(s, require_member(s, v, pointer, "type"), type_pointer);
    if (type == "grid") json_fail(s, type_pointer, "grid (OpenVDB) media are not supported yet: only 'homogeneous'");
    if (type != "homogeneous")
        json_fail(s, type_pointer, "unknown medium type '" + type + "' (expected 'homogeneous')");
    expect_keys(s, v, pointer, {"type", "sigma_a", "sigma_s", "g", "emission", "scale"});
    Medium m;
    m.name = name;
    // read_rgb refuses negative components, naming the key.
    if (const Json* a = find_member(v, "sigma_a")) m.sigma_a = read_rgb(s, *a, json_child(pointer, "sigma_a"));
    if (const Json* sc = find_member(v, "sigma_s")) m.sigma_s = read_rgb(s, *sc, json_child(pointer, "sigma_s"));
    if (const Json* e = find_member(v, "emission")) m.emission = read_rgb(s, *e, json_child(pointer, "emission"));
    if (const Json* g = find_member(v, "g")) {
        const std::string p = json_child(pointer, "g");
        m.g = read_float(s, *g, p);
        if (!(std::fabs(m.g) < 1.0f)) json_fail(s, p, "g must lie strictly between -1 and 1");
    }
    if (const Json* scale = find_member(v, "scale")) {
        const std::string p = json_child(pointer, "scale");
        const float k = read_float(s, *scale, p);
        if (k < 0.0f) json_fail(s, p, "scale must be non-negative");
        m.sigma_a = m.sigma_a * k;
        m.sigma_s = m.sigma_s * k;
        if (!std::isfinite(max_component(m.sigma_a + m.sigma_s))) json_fail(s, p, "scaled coefficients overflow");
    }
    return m;
}

}  // namespace

std::vector<Medium> read_media(const SceneJson& s, const Json& v, std::string_view pointer) {
    expect_object(s, v, pointer);
    std::vector<Medium> media;
    for (const auto& [name, medium] : v.items())
        media.push_back(read_medium(s, medium, json_child(pointer, name), name));
    return media;
}

}  // namespace sombra
