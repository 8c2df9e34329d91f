// Scene file → Scene: reads the JSON sections, checks every object's file
// before loading any mesh (a typo in the last object should not wait for the
// first one's million triangles), then loads the meshes and concatenates them
// into world-space geometry.
#include "io/scene_json/scene_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <utility>

#include "scene/corner_attributes.h"
#include "io/mesh_file.h"
#include "io/scene_json/scene_json.h"
#include "scene/transform.h"

namespace sombra {

namespace fs = std::filesystem;

namespace {

// Scene files describe; meshes belong in their own files. Bounds what a
// mistaken path (a huge mesh or a disk image) makes us read.
constexpr std::uintmax_t kMaxSceneFileBytes = 64u << 20;

// One entry of "objects", validated but not yet loaded.
struct ObjectSpec {
    std::string pointer;                    // "/objects/3"
    fs::path path;                          // the mesh file, relative to the working directory
    std::optional<std::uint32_t> material;  // override: index into Scene::materials
    Transform transform;
    bool is_quad_light = false;  // a quad light: no file behind it
};

ObjectSpec read_object(const SceneJson& s, const Json& v, std::string_view pointer, const fs::path& scene_path,
                       const std::map<std::string, std::uint32_t, std::less<>>& material_index) {
    expect_keys(s, v, pointer, {"file", "material", "transform"});
    ObjectSpec spec;
    spec.pointer = std::string(pointer);

    const std::string file_pointer = json_child(pointer, "file");
    const std::string& file = read_string(s, require_member(s, v, pointer, "file"), file_pointer);
    if (file.empty()) json_fail(s, file_pointer, "expected a file name, not an empty string");
    // The system reads a path up to its first NUL: "a.obj\u0000b" must not quietly load a.obj.
    if (file.find('\0') != std::string::npos) json_fail(s, file_pointer, "the file name contains a NUL character");
    spec.path = scene_path.parent_path() / fs::path(file);
    std::error_code ec;
    const fs::file_status status = fs::status(spec.path, ec);
    if (!fs::exists(status)) json_fail(s, file_pointer, "cannot open '" + file + "': no such file");
    if (fs::is_directory(status)) json_fail(s, file_pointer, "'" + file + "' is a folder, not a mesh file");
    // A device or a pipe could be read forever.
    if (!fs::is_regular_file(status)) json_fail(s, file_pointer, "'" + file + "' is not a regular file");
    if (fs::equivalent(spec.path, scene_path, ec))
        json_fail(s, file_pointer, "'" + file + "' is the scene file itself, not a mesh");

    if (const Json* m = find_member(v, "material")) {
        const std::string material_pointer = json_child(pointer, "material");
        const std::string& name = read_string(s, *m, material_pointer);
        const auto it = material_index.find(name);
        if (it == material_index.end()) json_fail(s, material_pointer, "unknown material '" + name + "'");
        spec.material = it->second;
    }
    if (const Json* t = find_member(v, "transform"))
        spec.transform = read_transform(s, *t, json_child(pointer, "transform"));
    return spec;
}

// Appends one loaded mesh to the world geometry (capacity already reserved):
// positions and the per-corner attributes to world space, indices offset,
// materials remapped.
void append_object(Scene& scene, const LoadedMesh& loaded, const ObjectSpec& spec, const SceneJson& s) {
    TriangleMesh& out = scene.geometry;
    const TriangleMesh& in = loaded.mesh;
    const std::string mesh_name = spec.path.string();

    scene.objects.push_back(SceneObject{spec.pointer, spec.is_quad_light ? std::string{} : mesh_name,
                                        static_cast<std::uint32_t>(out.triangles.size()),
                                        static_cast<std::uint32_t>(in.triangles.size())});
    const auto position_base = static_cast<std::uint32_t>(out.positions.size());
    for (const Vec3 p : in.positions) {
        const Vec3 q = transform_point(spec.transform, p);
        // Non-finite input positions are the loader's to drop (their triangles
        // are gone); finite ones must stay finite.
        if (is_finite(p) && !is_finite(q))
            json_fail(s, json_child(spec.pointer, "transform"), "a transformed vertex is not finite");
        out.positions.push_back(q);
    }

    // A mirroring transform (negative determinant) reverses every triangle's
    // winding; swapping two corners restores it, so the winding normal keeps
    // its side of the surface (spec §11, "sides for glass"). The normal, uv,
    // tangent and colour corners swap with them (append_corner_attributes).
    const bool mirrored = determinant3(spec.transform) < 0;
    const std::uint32_t vertex_count = static_cast<std::uint32_t>(in.positions.size());
    for (Index3 t : in.triangles) {
        if (t[0] >= vertex_count || t[1] >= vertex_count || t[2] >= vertex_count)
            throw Error(mesh_name, "a triangle refers to a vertex that does not exist");
        if (mirrored) std::swap(t[1], t[2]);
        out.triangles.push_back({t[0] + position_base, t[1] + position_base, t[2] + position_base});
    }
    append_corner_attributes(out, in, spec.transform);

    if (spec.material) {
        out.material_ids.insert(out.material_ids.end(), in.triangles.size(), *spec.material);
        return;
    }
    const auto material_base = static_cast<std::uint32_t>(scene.materials.size());
    scene.materials.insert(scene.materials.end(), loaded.materials.begin(), loaded.materials.end());
    // The file's textures join the scene's table (shared by source), its materials' references renumbered.
    std::vector<std::uint32_t> texture_index(loaded.textures.size());
    for (std::size_t i = 0; i < loaded.textures.size(); ++i) texture_index[i] = add_texture(scene.textures, loaded.textures[i]);
    for (std::size_t i = material_base; i < scene.materials.size(); ++i) {
        MaterialTextures& t = scene.materials[i].textures;
        for_each_texture_ref(t, [&](TextureRef& r) {
            if (r.is_set()) r.texture = r.texture < texture_index.size() ? texture_index[r.texture] : kNoTexture;
        });
        scene.materials[i].textured = any_texture(t);
    }
    // Loaders give every face a material; guard against one that did not.
    std::optional<std::uint32_t> fallback;
    const auto fallback_id = [&] {
        if (!fallback) {
            fallback = static_cast<std::uint32_t>(scene.materials.size());
            scene.materials.push_back(default_material());
        }
        return *fallback;
    };
    const auto file_material_count = static_cast<std::uint32_t>(loaded.materials.size());
    for (std::size_t i = 0; i < in.triangles.size(); ++i) {
        const bool known = i < in.material_ids.size() && in.material_ids[i] < file_material_count;
        out.material_ids.push_back(known ? material_base + in.material_ids[i] : fallback_id());
    }
}

// A light a glTF file placed, carried by its object's transform: the
// position moves, the direction turns with the transform's linear part.
PunctualLight transform_light(PunctualLight light, const Transform& transform, const SceneJson& s,
                              const std::string& object_pointer) {
    const std::string where = json_child(object_pointer, "transform");
    if (light.type != LightType::Directional) {
        light.position = transform_point(transform, light.position);
        if (!is_finite(light.position)) json_fail(s, where, "a transformed light position is not finite");
    }
    if (light.type != LightType::Point) {
        const Vec3 direction = transform_vector(transform, light.direction);
        if (!is_finite(direction) || !(length(to_double(direction)) > 0))
            json_fail(s, where, "a transformed light direction is not finite");
        light.direction = unit_direction(direction);
    }
    return light;
}

std::string read_scene_text(const fs::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw Error(name, "cannot open scene file: no such file");
    if (fs::is_directory(status)) throw Error(name, "cannot open scene file: it is a folder");
    if (!fs::is_regular_file(status)) throw Error(name, "cannot open scene file: not a regular file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > kMaxSceneFileBytes)
        throw Error(name, "scene file is larger than " + std::to_string(kMaxSceneFileBytes >> 20) + " MiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(name, "cannot open scene file: permission denied or unreadable");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error(name, "cannot read scene file");
    return std::move(text).str();
}

}  // namespace

LoadedScene load_scene_file(const fs::path& path, Diagnostics& diag) {
    return load_scene_text(read_scene_text(path), path, diag);
}

LoadedScene load_scene_text(const std::string& text, const fs::path& path, Diagnostics& diag) {
    const SceneJson s{path.string(), diag};
    const Json root = parse_scene_json(text, s.name);
    expect_keys(s, root, "", {"render", "background", "environment", "camera", "materials", "lights", "objects"});

    LoadedScene out;
    Scene& scene = out.scene;
    if (const Json* v = find_member(root, "render")) out.settings = read_render(s, *v, "/render");
    if (const Json* v = find_member(root, "background")) scene.background = read_rgb(s, *v, "/background");
    scene.camera = read_camera(s, require_member(s, root, "", "camera"), "/camera");
    SceneTextures textures{path.parent_path(), &scene.textures};
    if (const Json* v = find_member(root, "materials")) scene.materials = read_materials(s, *v, "/materials", textures);
    SceneLights lights;
    if (const Json* v = find_member(root, "lights")) lights = read_lights(s, *v, "/lights");
    scene.lights = std::move(lights.punctual);
    if (const Json* v = find_member(root, "environment")) {
        if (find_member(root, "background"))
            json_fail(s, "/environment", "give either 'background' or 'environment', not both (the map replaces the background)");
        scene.environment = read_environment(s, *v, "/environment", path.parent_path());
    }

    std::map<std::string, std::uint32_t, std::less<>> material_index;
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        material_index.emplace(scene.materials[i].name, static_cast<std::uint32_t>(i));

    const Json& objects = require_member(s, root, "", "objects");
    expect_array(s, objects, "/objects");
    if (objects.empty()) json_fail(s, "/objects", "at least one object is required");
    std::vector<ObjectSpec> specs;
    specs.reserve(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i)
        specs.push_back(read_object(s, objects[i], json_child("/objects", i), path, material_index));

    // Quad lights join the geometry after the objects, through the same
    // assembly: each is a two-triangle mesh with its own material.
    std::vector<LoadedMesh> quad_meshes;
    std::vector<ObjectSpec> quad_specs;
    for (const QuadLight& q : lights.quads) {
        quad_meshes.push_back(make_quad_light_mesh(q));
        quad_specs.push_back(ObjectSpec{q.pointer, "quad light " + q.pointer, std::nullopt, Transform{}, true});
    }

    // Load everything first so the world arrays are sized once, exactly. A
    // file used by several objects (one sphere, five materials) is read once.
    std::vector<LoadedMesh> meshes;
    std::vector<std::size_t> mesh_of(specs.size());
    std::vector<std::size_t> last_use;
    std::map<fs::path, std::size_t> loaded_index;
    std::size_t positions = 0, triangles = 0, normals = 0, uvs = 0, tangents = 0, colors = 0;
    bool any_normals = false, any_uvs = false, any_tangents = false, any_colors = false;
    for (std::size_t i = 0; i < specs.size(); ++i) {
        const ObjectSpec& spec = specs[i];
        std::error_code ec;
        fs::path key = fs::canonical(spec.path, ec);
        if (ec) key = spec.path;
        const auto [it, is_new] = loaded_index.try_emplace(key, meshes.size());
        if (is_new) {
            meshes.push_back(load_mesh_file(spec.path, diag));
            last_use.push_back(i);
        }
        mesh_of[i] = it->second;
        last_use[it->second] = i;
        const TriangleMesh& m = meshes[it->second].mesh;
        if (m.triangles.empty()) json_warn(s, json_child(spec.pointer, "file"), "the mesh has no triangles");
        positions += m.positions.size();
        triangles += m.triangles.size();
        normals += m.normals.size();
        any_normals = any_normals || m.has_normals();
        uvs += m.uvs.size();
        any_uvs = any_uvs || m.has_uvs();
        tangents += m.tangents.size();
        any_tangents = any_tangents || m.has_tangents();
        colors += m.colors.size();
        any_colors = any_colors || m.has_colors();
    }
    for (const LoadedMesh& q : quad_meshes) {
        positions += q.mesh.positions.size();
        triangles += q.mesh.triangles.size();
    }
    // Indices are 32-bit; kNoNormal is reserved.
    constexpr std::size_t kMaxIndex = std::numeric_limits<std::uint32_t>::max() - 1;
    if (positions > kMaxIndex || normals > kMaxIndex || uvs > kMaxIndex || tangents > kMaxIndex ||
        colors > kMaxIndex || triangles > kMaxIndex)
        json_fail(s, "/objects", "the scene has more than " + std::to_string(kMaxIndex) + " vertices or triangles");

    TriangleMesh& world = scene.geometry;
    world.positions.reserve(positions);
    world.triangles.reserve(triangles);
    world.material_ids.reserve(triangles);
    if (any_normals) {
        world.normals.reserve(normals);
        world.normal_indices.reserve(triangles);
    }
    if (any_uvs) {
        world.uvs.reserve(uvs);
        world.uv_indices.reserve(triangles);
    }
    if (any_tangents) {
        world.tangents.reserve(tangents);
        world.tangent_indices.reserve(triangles);
    }
    if (any_colors) {
        world.colors.reserve(colors);
        world.color_indices.reserve(triangles);
    }
    for (std::size_t i = 0; i < specs.size(); ++i) {
        // Lights a glTF file places move with its object (§13, §16).
        for (const PunctualLight& light : meshes[mesh_of[i]].lights)
            scene.lights.push_back(transform_light(light, specs[i].transform, s, specs[i].pointer));
        append_object(scene, meshes[mesh_of[i]], specs[i], s);
        // Free each file's mesh after its last object: peak memory stays near two copies.
        if (last_use[mesh_of[i]] == i) meshes[mesh_of[i]] = LoadedMesh{};
    }
    for (std::size_t i = 0; i < quad_meshes.size(); ++i) append_object(scene, quad_meshes[i], quad_specs[i], s);
    mark_complete_corners(scene.geometry);
    return out;
}

namespace {

constexpr float kFovDegrees = 40.0f;

// Radiance of a grey kd = 0.8 Lambertian surface facing the key light at the
// sphere's centre: L = I/d² · kd/π. 0.45 leaves headroom for light from the
// fill and rim lights overlapping it.
constexpr float kKeyRadiance = 0.45f;

struct Sphere {
    Vec3 centre;
    float radius;
};

Sphere bounding_sphere(const TriangleMesh& mesh) {
    Vec3 lo{INFINITY}, hi{-INFINITY};
    for (const Index3& tri : mesh.triangles)
        for (std::uint32_t v : tri) {
            lo = min(lo, mesh.positions[v]);
            hi = max(hi, mesh.positions[v]);
        }
    const float radius = 0.5f * length(hi - lo);
    // A single point (all triangles degenerate) still gets a usable frame.
    return {(lo + hi) * 0.5f, radius > 0.0f ? radius : 1.0f};
}

}  // namespace

LoadedScene make_quicklook_scene(const std::filesystem::path& model, Diagnostics& diag) {
    LoadedMesh loaded = load_mesh_file(model, diag);
    const Sphere sphere = bounding_sphere(loaded.mesh);

    LoadedScene out;
    Scene& scene = out.scene;
    scene.background = Vec3{0.02f};
    scene.materials = std::move(loaded.materials);
    scene.textures = std::move(loaded.textures);
    for (Material& m : scene.materials) m.textured = any_texture(m.textures);
    scene.geometry = std::move(loaded.mesh);
    mark_complete_corners(scene.geometry);
    scene.objects.push_back(SceneObject{model.filename().string(), model.string(), 0,
                                        static_cast<std::uint32_t>(scene.geometry.triangle_count())});

    // A glTF file's own camera (its first) and point lights replace the
    // automatic framing and lighting; its aspect ratio sets the image's
    // height for the default width.
    if (loaded.camera) {
        const ModelCamera& c = *loaded.camera;
        scene.camera.look_at = CameraLookAt{c.origin, c.origin + c.forward, c.up, c.yfov_degrees};
        if (c.aspect > 0) {
            const float height = std::round(static_cast<float>(out.settings.width) / c.aspect);
            out.settings.height = static_cast<int>(std::clamp(height, 1.0f, static_cast<float>(kMaxImageSide)));
        }
    }
    scene.lights = std::move(loaded.lights);

    // Far enough that the sphere fits the vertical field of view (the
    // horizontal one is wider for landscape images), with a 10 % margin.
    const float half_fov = kFovDegrees * 0.5f * std::numbers::pi_v<float> / 180.0f;
    const float distance = 1.1f * sphere.radius / std::sin(half_fov);
    const Vec3 view_dir = normalize(Vec3{0.0f, 0.35f, 1.0f});  // front, a little above
    if (!scene.camera.look_at)
        scene.camera.look_at = CameraLookAt{sphere.centre + distance * view_dir, sphere.centre, Vec3{0, 1, 0}, kFovDegrees};
    if (!scene.lights.empty()) return out;

    // Three-point lighting around the camera, at a few radii from the model.
    auto light_at = [&](Vec3 direction, float distance_in_radii, float share) {
        const float d = distance_in_radii * sphere.radius;
        const float intensity = share * kKeyRadiance * std::numbers::pi_v<float> / 0.8f * d * d;
        return make_point_light(sphere.centre + d * normalize(direction), Vec3{intensity});
    };
    scene.lights.push_back(light_at({-1.0f, 1.4f, 1.3f}, 4.0f, 1.0f));   // key: upper left, front
    scene.lights.push_back(light_at({1.2f, 0.3f, 1.0f}, 4.0f, 0.35f));   // fill: right, low
    scene.lights.push_back(light_at({0.3f, 1.2f, -1.2f}, 4.0f, 0.5f));   // rim: behind, above
    return out;
}

}  // namespace sombra
