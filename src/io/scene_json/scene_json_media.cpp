// The scene file's "media" (spec §26): named participating media, checked
// key by key, the render's and the camera's medium, and the objects that
// bound media. Homogeneous media only in this version of sombra; a grid
// (OpenVDB) medium is refused in one line until it is built.
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/scene_json/scene_json.h"
#include "io/vdb/vdb_reader.h"
#include "scene/mesh_edges.h"
#include "scene/scene_builder.h"

namespace sombra {

namespace {

// A grid medium's density: "file" (relative to the scene's folder) and
// "grid" (default "density"), the reader's problems naming the key.
std::shared_ptr<const DensityGrid> read_density(const SceneJson& s, const Json& v, std::string_view pointer) {
    const std::string file_pointer = json_child(pointer, "file");
    const std::string& file = read_string(s, require_member(s, v, pointer, "file"), file_pointer);
    if (file.empty() || file.find('\0') != std::string::npos) json_fail(s, file_pointer, "expected a file name");
    std::string grid = "density";
    const std::string grid_pointer = json_child(pointer, "grid");
    if (const Json* g = find_member(v, "grid")) grid = read_string(s, *g, grid_pointer);
    const std::filesystem::path path = std::filesystem::path(s.name).parent_path() / file;
    try {
        return std::make_shared<const DensityGrid>(read_vdb_density(path, grid));
    } catch (const Error& e) {
        const bool about_grid = e.message().rfind("no grid", 0) == 0 || e.message().rfind("grid '", 0) == 0 ||
                                e.message().rfind("voxel", 0) == 0;
        json_fail(s, about_grid ? grid_pointer : file_pointer, "'" + file + "': " + e.message());
    }
}

Medium read_medium(const SceneJson& s, const Json& v, std::string_view pointer, const std::string& name) {
    expect_object(s, v, pointer);
    const std::string type_pointer = json_child(pointer, "type");
    const std::string& type = read_string(s, require_member(s, v, pointer, "type"), type_pointer);
    if (type != "homogeneous" && type != "grid")
        json_fail(s, type_pointer, "unknown medium type '" + type + "' (expected 'homogeneous' or 'grid')");
    Medium m;
    m.name = name;
    if (type == "grid") {
        if (find_member(v, "emission"))
            json_fail(s, json_child(pointer, "emission"), "grid media emit nothing in this version of sombra");
        expect_keys(s, v, pointer, {"type", "file", "grid", "sigma_a", "sigma_s", "g", "scale"});
        m.density = read_density(s, v, pointer);
    } else {
        expect_keys(s, v, pointer, {"type", "sigma_a", "sigma_s", "g", "emission", "scale"});
    }
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

// The index of the medium `name` names, or an error at `pointer`.
std::uint32_t find_medium(const SceneJson& s, const std::vector<Medium>& media, const Json& name,
                          const std::string& pointer) {
    const std::string& wanted = read_string(s, name, pointer);
    for (std::size_t i = 0; i < media.size(); ++i)
        if (media[i].name == wanted) return static_cast<std::uint32_t>(i);
    json_fail(s, pointer, "no medium '" + wanted + "' in /media");
}

// True when light can enter through a surface of `m`.
bool lets_light_in(const Material& m) {
    return m.type == MaterialType::Dielectric || m.type == MaterialType::Interface ||
           (m.type == MaterialType::Pbr && (m.transmission > 0.0f || m.textures.transmission.is_set()));
}

// An object's triangles: triangles first … first + count − 1 of `mesh`
// (its instanced mesh, or its range of the world geometry).
struct ObjectTriangles {
    const TriangleMesh& mesh;
    std::uint32_t first, count;
};
ObjectTriangles object_triangles(const Scene& scene, const SceneObject& object) {
    if (object.instance_count == 0) return {scene.geometry, object.first_triangle, object.triangle_count};
    const TriangleMesh& mesh = scene.instanced_meshes[scene.instances[object.first_instance].mesh];
    return {mesh, 0, static_cast<std::uint32_t>(mesh.triangles.size())};
}

// The materials on an object's triangles, each index once.
std::vector<std::uint32_t> object_materials(const Scene& scene, const ObjectTriangles& triangles) {
    std::vector<bool> seen(scene.materials.size());
    std::vector<std::uint32_t> ids;
    for (std::uint32_t t = triangles.first; t < triangles.first + triangles.count; ++t)
        if (const std::uint32_t id = triangles.mesh.material_ids[t]; id < seen.size() && !seen[id]) {
            seen[id] = true;
            ids.push_back(id);
        }
    return ids;
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

namespace sombra {

void read_scene_media(const SceneJson& s, const Json& root, SceneBuilder& builder) {
    std::vector<Medium> media;
    if (const Json* v = find_member(root, "media")) media = read_media(s, *v, "/media");
    std::uint32_t render_medium = kNoMedium;
    const Json* render = find_member(root, "render");
    if (const Json* name = render != nullptr ? find_member(*render, "medium") : nullptr) {
        render_medium = find_medium(s, media, *name, "/render/medium");
        if (media[render_medium].density)
            json_fail(s, "/render/medium",
                      "the grid medium '" + media[render_medium].name +
                          "' cannot fill the scene: make it an object's \"interior\"");
        // What lies infinitely far is hidden by a medium without end (spec §26, as in Cycles).
        bool far = find_member(root, "environment") != nullptr;
        if (const Json* background = find_member(root, "background"))
            far = far || (background->is_array() && max_component(read_rgb(s, *background, "/background")) > 0.0f);
        if (const Json* lights = find_member(root, "lights"); lights != nullptr && lights->is_array())
            for (const Json& light : *lights)
                if (const Json* type = light.is_object() ? find_member(light, "type") : nullptr)
                    far = far || (type->is_string() && *type == "directional");
        if (far && max_component(extinction(media[render_medium])) > 0.0f)
            json_warn(s, "/render/medium",
                      "the medium '" + media[render_medium].name +
                          "' fills space without end: the environment, the background and directional lights, "
                          "infinitely far, are hidden by it");
    }
    std::optional<std::uint32_t> camera_medium;
    if (const Json* camera = find_member(root, "camera"); camera != nullptr && camera->is_object())
        if (const Json* name = find_member(*camera, "medium"))
            camera_medium = find_medium(s, media, *name, "/camera/medium");
    builder.set_media(std::move(media), render_medium);
    if (camera_medium) builder.set_camera_medium(*camera_medium);
}

std::optional<MediumBoundary> read_object_media(const SceneJson& s, const Json& v, std::string_view pointer,
                                                const std::vector<Medium>& media, std::uint32_t render_medium) {
    const Json* interior = find_member(v, "interior");
    const Json* exterior = find_member(v, "exterior");
    if (interior == nullptr) {
        if (exterior != nullptr)
            json_fail(s, json_child(pointer, "exterior"), "'exterior' needs 'interior' (the medium the object bounds)");
        return std::nullopt;
    }
    MediumBoundary boundary;
    boundary.interior = find_medium(s, media, *interior, json_child(pointer, "interior"));
    boundary.exterior =
        exterior != nullptr ? find_medium(s, media, *exterior, json_child(pointer, "exterior")) : render_medium;
    if (boundary.exterior != kNoMedium && media[boundary.exterior].density)
        json_fail(s, json_child(pointer, "exterior"),
                  "a grid medium fills only the interior of the object that places it");
    return boundary;
}

void check_medium_objects(const SceneJson& s, const Scene& scene) {
    for (const SceneObject& object : scene.objects) {
        if (!object.bounds_medium) continue;
        const ObjectTriangles triangles = object_triangles(scene, object);
        const std::vector<std::uint32_t> ids = object_materials(scene, triangles);
        bool enters = false;
        for (const std::uint32_t id : ids) {
            const Material& m = scene.materials[id];
            enters = enters || lets_light_in(m);
            if (m.type == MaterialType::Pbr && std::isfinite(m.attenuation_distance))
                json_warn(s, json_child(object.name, "interior"),
                          "the interior replaces the attenuation of material '" + m.name + "' (KHR_materials_volume)");
        }
        if (!enters)
            json_warn(s, json_child(object.name, "interior"),
                      "the object's material is opaque: its interior medium is never entered (use a dielectric, "
                      "a transmissive pbr or \"interface\")");
        const std::size_t open = open_edge_count(triangles.mesh, triangles.first, triangles.count);
        if (open > 0)
            json_warn(s, json_child(object.name, "interior"),
                      "the object's surface is not closed (" + std::to_string(open) +
                          " edges belong to one triangle only): light leaks through its holes into and out of "
                          "its medium");
    }
}

}  // namespace sombra
