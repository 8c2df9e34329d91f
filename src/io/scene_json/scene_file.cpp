// Scene file → Scene: reads the JSON sections, checks every object's file
// before loading any mesh (a typo in the last object should not wait for the
// first one's million triangles), then loads the meshes and hands them to the
// scene's builder (scene/scene_builder.h), which places them in world space.
#include "io/scene_json/scene_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "io/mesh_file.h"
#include "io/scene_json/scene_json.h"
#include "scene/scene_builder.h"
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
    Transform transform;                    // keyed: its value at the first frame
    std::vector<TransformKey> keys;         // spec §22; empty when the transform is fixed
    // Spec §23: each entry applied after `transform`; empty: drawn once.
    std::vector<Transform> instances;
    bool is_quad_light = false;           // a quad light: no file behind it
    const LoadedMesh* given = nullptr;    // a mesh made from arrays ("mesh": i), no file behind it
    bool interface = false;               // "material": "interface" (spec §26)
    std::optional<MediumBoundary> media;  // "interior" and "exterior" (spec §26)
    // A grid interior placed once per drawing of the object (its transform,
    // then each instance): Scene::media indices, one per instance (or one).
    std::vector<std::uint32_t> grid_interiors;
};

// Where a MeshFileCache keeps a mesh file: its absolute path, "." and ".." resolved.
fs::path cache_key(const fs::path& path) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(path, ec);
    return (ec ? path : absolute).lexically_normal();
}

// The object's file, checked to be one before any mesh is read (unless
// `cache` holds it: read before, it may have gone since).
void read_object_file(const SceneJson& s, const Json& v, std::string_view pointer, const fs::path& scene_path,
                      const MeshFileCache* cache, ObjectSpec& spec) {
    const std::string file_pointer = json_child(pointer, "file");
    const std::string& file = read_string(s, require_member(s, v, pointer, "file"), file_pointer);
    if (file.empty()) json_fail(s, file_pointer, "expected a file name, not an empty string");
    // The system reads a path up to its first NUL: "a.obj\u0000b" must not quietly load a.obj.
    if (file.find('\0') != std::string::npos) json_fail(s, file_pointer, "the file name contains a NUL character");
    spec.path = scene_path.parent_path() / fs::path(file);
    if (cache != nullptr) {
        const auto cached = cache->meshes.find(cache_key(spec.path));
        if (cached != cache->meshes.end() && cached->second != nullptr) return;
    }
    std::error_code ec;
    const fs::file_status status = fs::status(spec.path, ec);
    if (!fs::exists(status))
        json_fail(s, file_pointer, "cannot open '" + file + "': no such file " + looked_for(spec.path));
    if (fs::is_directory(status)) json_fail(s, file_pointer, "'" + file + "' is a folder, not a mesh file");
    // A device or a pipe could be read forever.
    if (!fs::is_regular_file(status)) json_fail(s, file_pointer, "'" + file + "' is not a regular file");
    if (fs::equivalent(spec.path, scene_path, ec))
        json_fail(s, file_pointer, "'" + file + "' is the scene file itself, not a mesh");
}

ObjectSpec read_object(const SceneJson& s, const Json& v, std::string_view pointer, const fs::path& scene_path,
                       const std::map<std::string, std::uint32_t, std::less<>>& material_index,
                       std::span<const LoadedMesh* const> given_meshes, const MeshFileCache* cache, double start_time,
                       const Scene& scene) {
    ObjectSpec spec;
    spec.pointer = std::string(pointer);
    if (given_meshes.empty()) {
        expect_keys(s, v, pointer, {"file", "material", "transform", "instances", "interior", "exterior"});
        read_object_file(s, v, pointer, scene_path, cache, spec);
    } else {
        expect_keys(s, v, pointer, {"file", "mesh", "material", "transform", "instances", "interior", "exterior"});
        if (const Json* m = find_member(v, "mesh")) {
            if (find_member(v, "file")) json_fail(s, pointer, "give either 'file' or 'mesh', not both");
            const std::int64_t i =
                read_integer(s, *m, json_child(pointer, "mesh"), 0, static_cast<std::int64_t>(given_meshes.size()) - 1);
            spec.given = given_meshes[static_cast<std::size_t>(i)];
            spec.path = "mesh " + std::to_string(i);
        } else {
            read_object_file(s, v, pointer, scene_path, cache, spec);
        }
    }

    if (const Json* m = find_member(v, "material")) {
        const std::string material_pointer = json_child(pointer, "material");
        const std::string& name = read_string(s, *m, material_pointer);
        const auto it = material_index.find(name);
        spec.interface = name == "interface";
        if (it != material_index.end())
            spec.material = it->second;
        else if (!spec.interface)
            json_fail(s, material_pointer, "unknown material '" + name + "'");
    }
    spec.media = read_object_media(s, v, pointer, scene.media, scene.render_medium);
    if (const Json* t = find_member(v, "transform")) {
        if (t->is_object()) {
            spec.keys = read_transform_keys(s, *t, json_child(pointer, "transform"));
            spec.transform = interpolate_transform(spec.keys, start_time);
        } else {
            spec.transform = read_transform(s, *t, json_child(pointer, "transform"));
        }
    }
    if (const Json* list = find_member(v, "instances")) {
        const std::string list_pointer = json_child(pointer, "instances");
        expect_array(s, *list, list_pointer);
        if (list->empty()) json_fail(s, list_pointer, "expected at least one instance (each a transform list)");
        if (list->size() > kMaxInstances)
            json_fail(s, list_pointer, "more than " + std::to_string(kMaxInstances) + " instances");
        spec.instances.reserve(list->size());
        for (std::size_t k = 0; k < list->size(); ++k)
            spec.instances.push_back(read_transform(s, (*list)[k], json_child(list_pointer, k)));
    }
    return spec;
}

// What an object's file draws once joins the scene: placed by its
// transform, with the scene's material when it names one, else its file's
// own. The builder's problems become errors naming the object's transform
// or its file. An object with instances is stored once and drawn per
// instance, unless it has just one: a copy placed in the world geometry is
// as small and saves the instance's ray transform (spec §23). A keyed
// object is always instanced (a single identity instance when it has no
// list): a new moment then moves instances and keeps its mesh's structure
// (spec §22).
void add_whole(SceneBuilder& builder, const LoadedMesh& loaded, ObjectSpec spec, const SceneJson& s,
               SceneAnimation& animation) {
    if (!spec.keys.empty()) {
        if (spec.instances.empty()) spec.instances.push_back(Transform{});
        animation.objects.push_back(
            AnimatedObject{spec.pointer, static_cast<std::uint32_t>(builder.scene().instances.size()), spec.keys,
                           std::vector<Transform>(spec.instances.size()), spec.instances});
    }
    const bool instanced = spec.instances.size() > 1 || !spec.keys.empty();
    const std::string mesh_name = spec.path.string();
    MeshPlacement placement{spec.pointer, spec.is_quad_light ? std::string{} : mesh_name, spec.transform, spec.material,
                            spec.media};
    if (placement.media) placement.media->instance_interiors = spec.grid_interiors;
    std::size_t bad = 0;
    MeshProblem problem = MeshProblem::None;
    if (!instanced && spec.instances.size() == 1) placement.transform = compose(spec.transform, spec.instances[0]);
    if (!instanced)
        problem = builder.add_mesh(loaded.mesh, loaded.materials, loaded.textures, placement);
    else
        problem =
            builder.add_instanced_mesh(loaded.mesh, loaded.materials, loaded.textures, placement, spec.instances, &bad);
    const std::string where = !instanced && spec.instances.size() == 1
                                  ? json_child(json_child(spec.pointer, "instances"), 0)
                                  : json_child(spec.pointer, "transform");
    const std::string instance = json_child(json_child(spec.pointer, "instances"), bad);
    switch (problem) {
        case MeshProblem::None: return;
        case MeshProblem::NonFinitePlacement:
            json_fail(s, instanced ? instance : where, "a transformed vertex is not finite");
        case MeshProblem::BadVertexIndex: throw Error(mesh_name, "a triangle refers to a vertex that does not exist");
        case MeshProblem::SingularInstance:
            json_fail(s, instance,
                      "the object's transform and this instance together are not invertible in float (determinant 0 or "
                      "overflowing)");
        case MeshProblem::TooManyInstances:
            json_fail(s, json_child(spec.pointer, "instances"),
                      "the scene would hold more than " + std::to_string(kMaxInstances) + " instances");
    }
}

// A glTF file's meshes drawn several times (spec §23): each instance placed
// in the file, then by the object's transform, then by each of the
// object's instances (all of a part's for the first, then the next). The
// builder's problems name the glTF node as well as the object.
void add_parts(SceneBuilder& builder, const LoadedMesh& loaded, const ObjectSpec& spec, const SceneJson& s,
               SceneAnimation& animation) {
    const std::string mesh_name = spec.path.string();
    MeshPlacement placement{spec.pointer, mesh_name, std::nullopt, spec.material, spec.media};
    const std::size_t copies = std::max<std::size_t>(1, spec.instances.size());
    const std::string list = json_child(spec.pointer, spec.instances.empty() ? "transform" : "instances");
    const std::string too_many = "the scene would hold more than " + std::to_string(kMaxInstances) + " instances";
    std::vector<Transform> world;
    for (const InstancedPart& part : loaded.instanced) {
        const std::size_t n = part.instances.size();
        if (n > kMaxInstances / copies) json_fail(s, list, too_many);
        world.clear();
        world.reserve(n * copies);
        if (placement.media && !spec.grid_interiors.empty()) {
            // Each drawing's grid is its object copy's (place_grid_media).
            std::vector<std::uint32_t>& own = placement.media->instance_interiors;
            own.clear();
            for (const std::uint32_t grid : spec.grid_interiors) own.insert(own.end(), n, grid);
        }
        for (std::size_t j = 0; j < copies; ++j) {
            const Transform object =
                spec.instances.empty() ? spec.transform : compose(spec.transform, spec.instances[j]);
            for (const Transform& t : part.instances) world.push_back(compose(t, object));
        }
        if (!part.nodes.empty()) {
            // Animated in the file (spec §22): its node's pose at each moment, then the object's
            // transform (keyed or fixed), then the object's instances.
            AnimatedObject moving{spec.pointer,
                                  static_cast<std::uint32_t>(builder.scene().instances.size()),
                                  spec.keys.empty() ? std::vector<TransformKey>{{0.0, spec.transform}} : spec.keys,
                                  {},
                                  {},
                                  loaded.animation,
                                  {},
                                  mesh_name};
            for (std::size_t j = 0; j < copies; ++j)
                for (std::size_t k = 0; k < n; ++k) {
                    moving.before.push_back(part.local[k]);
                    moving.nodes.push_back(part.nodes[k]);
                    moving.after.push_back(spec.instances.empty() ? Transform{} : spec.instances[j]);
                }
            animation.objects.push_back(std::move(moving));
        } else if (!spec.keys.empty()) {
            // Keyed: the file's placement acts before the keyed transform, the object's instances after.
            AnimatedObject moving{
                spec.pointer, static_cast<std::uint32_t>(builder.scene().instances.size()), spec.keys, {}, {}};
            for (std::size_t j = 0; j < copies; ++j)
                for (const Transform& t : part.instances) {
                    moving.before.push_back(t);
                    moving.after.push_back(spec.instances.empty() ? Transform{} : spec.instances[j]);
                }
            animation.objects.push_back(std::move(moving));
        }
        std::size_t bad = 0;
        const MeshProblem problem =
            builder.add_instanced_mesh(part.mesh, loaded.materials, loaded.textures, placement, world, &bad);
        const std::string node = mesh_name + ": " + instance_name(part, bad % n) + ": ";
        const std::string where = spec.instances.empty() ? list : json_child(list, bad / n);
        switch (problem) {
            case MeshProblem::None: continue;
            case MeshProblem::NonFinitePlacement: json_fail(s, where, node + "a transformed vertex is not finite");
            case MeshProblem::BadVertexIndex:
                throw Error(mesh_name, "a triangle refers to a vertex that does not exist");
            case MeshProblem::SingularInstance:
                json_fail(s, where, node + "the node's and the object's transforms together are not invertible");
            case MeshProblem::TooManyInstances: json_fail(s, list, too_many);
        }
    }
}

// One object joins the scene: what its file draws once as add_whole says,
// the meshes drawn several times as add_parts says.
void add_object(SceneBuilder& builder, const LoadedMesh& loaded, const ObjectSpec& spec, const SceneJson& s,
                SceneAnimation& animation) {
    if (!loaded.mesh.triangles.empty() || loaded.instanced.empty()) add_whole(builder, loaded, spec, s, animation);
    add_parts(builder, loaded, spec, s, animation);
}

// An object whose interior is a grid medium places its own copy of it per
// drawing (spec §26): the grid's index-to-world transform, then the object's,
// then the instance's. A camera inside a grid medium is in its first placement.
void place_grid_media(const SceneJson& s, std::vector<ObjectSpec>& specs, SceneBuilder& builder) {
    std::vector<std::uint32_t> first_placement(builder.scene().media.size(), kNoMedium);
    for (ObjectSpec& spec : specs) {
        if (!spec.media || spec.media->interior == kNoMedium) continue;
        const std::uint32_t index = spec.media->interior;
        if (!builder.scene().media[index].density) continue;
        const std::size_t copies = std::max<std::size_t>(1, spec.instances.size());
        for (std::size_t j = 0; j < copies; ++j) {
            Medium placed = builder.scene().media[index];
            const Transform object =
                spec.instances.empty() ? spec.transform : compose(spec.transform, spec.instances[j]);
            if (!place_grid_medium(placed, object))
                json_fail(s,
                          spec.instances.empty() ? json_child(spec.pointer, "interior")
                                                 : json_child(json_child(spec.pointer, "instances"), j),
                          "the grid's and the object's transforms together are not invertible");
            spec.grid_interiors.push_back(builder.add_medium(std::move(placed)));
        }
        spec.media->interior = spec.grid_interiors.front();
        if (first_placement[index] == kNoMedium) first_placement[index] = spec.media->interior;
    }
    const std::optional<std::uint32_t> camera = builder.scene().camera_medium;
    if (camera && *camera < first_placement.size() && builder.scene().media[*camera].density) {
        if (first_placement[*camera] == kNoMedium)
            json_fail(s, "/camera/medium",
                      "the grid medium '" + builder.scene().media[*camera].name + "' is no object's interior");
        builder.set_camera_medium(first_placement[*camera]);
    }
}

// A light a glTF file placed, carried by its object's transform.
PunctualLight placed_light(PunctualLight light, const Transform& transform, const SceneJson& s,
                           const std::string& object_pointer) {
    switch (transform_light(light, transform)) {
        case LightPlacement::Ok: break;
        case LightPlacement::NonFinitePosition:
            json_fail(s, json_child(object_pointer, "transform"), "a transformed light position is not finite");
        case LightPlacement::NonFiniteDirection:
            json_fail(s, json_child(object_pointer, "transform"), "a transformed light direction is not finite");
    }
    return light;
}

}  // namespace

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

LoadedScene load_scene_file(const fs::path& path, Diagnostics& diag) {
    return load_scene_text(read_scene_text(path), path, diag);
}

LoadedScene load_scene_text(const std::string& text, const fs::path& path, Diagnostics& diag,
                            std::span<const LoadedMesh* const> given_meshes, MeshFileCache* cache) {
    const SceneJson s{path.string(), diag};
    const Json root = parse_scene_json(text, s.name);
    expect_keys(s, root, "",
                {"render", "background", "environment", "camera", "materials", "lights", "objects", "animation",
                 "media"});
    SceneClock clock;
    if (const Json* v = find_member(root, "animation")) clock = read_animation(s, *v, "/animation");
    // The scene is built at its first frame's moment (spec §22).
    const double start_time = static_cast<double>(clock.first_frame) / clock.fps;
    SceneAnimation animation{clock.fps, clock.first_frame, clock.last_frame, {}, {}};

    LoadedScene out;
    SceneBuilder builder;
    if (const Json* v = find_member(root, "render")) out.settings = read_render(s, *v, "/render");
    read_scene_media(s, root, builder);
    if (const Json* v = find_member(root, "background")) builder.set_background(read_rgb(s, *v, "/background"));
    const Json& camera = require_member(s, root, "", "camera");
    if (camera.is_object() && find_member(camera, "keys")) {
        animation.camera = read_camera_keys(s, camera, "/camera");
        builder.set_camera(interpolate_camera(animation.camera, start_time));
    } else {
        builder.set_camera(read_camera(s, camera, "/camera"));
    }
    // The file's materials name their textures in the file's own table, which joins the scene's.
    std::vector<Material> materials;
    std::vector<Texture> material_textures;
    SceneTextures textures{path.parent_path(), &material_textures};
    if (const Json* v = find_member(root, "materials")) materials = read_materials(s, *v, "/materials", textures);
    builder.add_materials(materials, material_textures);
    SceneLights lights;
    if (const Json* v = find_member(root, "lights")) lights = read_lights(s, *v, "/lights");
    for (const PunctualLight& light : lights.punctual) builder.add_light(light);
    if (const Json* v = find_member(root, "environment")) {
        if (find_member(root, "background"))
            json_fail(s, "/environment",
                      "give either 'background' or 'environment', not both (the map replaces the background)");
        builder.set_environment(read_environment(s, *v, "/environment", path.parent_path()));
    }

    std::map<std::string, std::uint32_t, std::less<>> material_index;
    for (std::size_t i = 0; i < materials.size(); ++i)
        material_index.emplace(materials[i].name, static_cast<std::uint32_t>(i));

    const Json& objects = require_member(s, root, "", "objects");
    expect_array(s, objects, "/objects");
    if (objects.empty()) json_fail(s, "/objects", "at least one object is required");
    std::vector<ObjectSpec> specs;
    specs.reserve(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i)
        specs.push_back(read_object(s, objects[i], json_child("/objects", i), path, material_index, given_meshes, cache,
                                    start_time, builder.scene()));
    for (ObjectSpec& spec : specs)
        if (spec.interface) spec.material = builder.interface_material();
    place_grid_media(s, specs, builder);

    // Quad lights join the geometry after the objects, through the same
    // assembly: each is a two-triangle mesh with its own material.
    std::vector<LoadedMesh> quad_meshes;
    std::vector<ObjectSpec> quad_specs;
    for (const QuadLight& q : lights.quads) {
        quad_meshes.push_back(make_quad_light_mesh(q));
        ObjectSpec spec;
        spec.pointer = q.pointer;
        spec.path = "quad light " + q.pointer;
        spec.is_quad_light = true;
        quad_specs.push_back(std::move(spec));
    }

    // Load everything first so the world arrays are sized once, exactly. A
    // file used by several objects (one sphere, five materials) is read once.
    std::vector<std::shared_ptr<const LoadedMesh>> meshes;
    std::vector<std::size_t> mesh_of(specs.size());
    std::vector<std::size_t> last_use;
    std::map<fs::path, std::size_t> loaded_index;
    MeshSizes sizes;
    for (std::size_t i = 0; i < specs.size(); ++i) {
        const ObjectSpec& spec = specs[i];
        // Instanced objects keep their own arrays: no room in the world's.
        const bool flattened = spec.instances.size() <= 1 && spec.keys.empty();
        if (spec.given) {
            if (flattened) sizes += sizes_of(spec.given->mesh);
            continue;
        }
        // One file through two names (a link) is read once; a cache knows files by their absolute path.
        std::error_code ec;
        fs::path key = fs::canonical(spec.path, ec);
        if (ec || cache != nullptr) key = cache_key(spec.path);
        const auto [it, is_new] = loaded_index.try_emplace(key, meshes.size());
        if (is_new) {
            std::shared_ptr<const LoadedMesh>* cached = nullptr;
            if (cache != nullptr) cached = &cache->meshes[key];
            if (cached != nullptr && *cached != nullptr)
                meshes.push_back(*cached);
            else
                meshes.push_back(std::make_shared<const LoadedMesh>(load_mesh_file(spec.path, diag)));
            if (cached != nullptr) *cached = meshes.back();
            last_use.push_back(i);
        }
        mesh_of[i] = it->second;
        last_use[it->second] = i;
        const TriangleMesh& m = meshes[it->second]->mesh;
        if (m.triangles.empty() && meshes[it->second]->instanced.empty())
            json_warn(s, json_child(spec.pointer, "file"), "the mesh has no triangles");
        if (flattened) sizes += sizes_of(m);
    }
    for (const LoadedMesh& q : quad_meshes) sizes += sizes_of(q.mesh);
    // Indices are 32-bit; kNoNormal is reserved.
    constexpr std::size_t kMaxIndex = std::numeric_limits<std::uint32_t>::max() - 1;
    if (sizes.positions > kMaxIndex || sizes.normals > kMaxIndex || sizes.uvs > kMaxIndex ||
        sizes.tangents > kMaxIndex || sizes.colors > kMaxIndex || sizes.triangles > kMaxIndex)
        json_fail(s, "/objects", "the scene has more than " + std::to_string(kMaxIndex) + " vertices or triangles");

    builder.reserve(sizes);
    for (std::size_t i = 0; i < specs.size(); ++i) {
        if (specs[i].given) {
            add_object(builder, *specs[i].given, specs[i], s, animation);
            continue;
        }
        // Lights a glTF file places move with its object (§13, §16), and on
        // animated nodes or a keyed object with the clock (§22).
        const LoadedMesh& file = *meshes[mesh_of[i]];
        for (std::size_t j = 0; j < file.lights.size(); ++j) {
            const bool on_node = j < file.light_nodes.size() && file.light_nodes[j] >= 0;
            const auto add = [&](const Transform* instance) {  // null: the object has no "instances"
                const Transform placed = instance ? compose(specs[i].transform, *instance) : specs[i].transform;
                if (on_node || !specs[i].keys.empty())
                    animation.lights.push_back(AnimatedLight{
                        static_cast<std::uint32_t>(builder.scene().lights.size()),
                        on_node ? file.lights_in_nodes[j] : file.lights[j], on_node ? file.animation : nullptr,
                        on_node ? static_cast<std::uint32_t>(file.light_nodes[j]) : 0u, specs[i].keys,
                        specs[i].keys.empty() ? placed : (instance ? *instance : Transform{}), specs[i].pointer});
                builder.add_light(placed_light(file.lights[j], placed, s, specs[i].pointer));
            };
            if (specs[i].instances.empty()) add(nullptr);
            for (const Transform& instance : specs[i].instances) add(&instance);
        }
        add_object(builder, file, specs[i], s, animation);
        // Free each file's mesh after its last object (unless a cache keeps
        // it): peak memory stays near two copies.
        if (last_use[mesh_of[i]] == i) meshes[mesh_of[i]].reset();
    }
    for (std::size_t i = 0; i < quad_meshes.size(); ++i)
        add_object(builder, quad_meshes[i], quad_specs[i], s, animation);
    out.scene = builder.finish();
    check_medium_objects(s, out.scene);
    if (find_member(root, "animation") || !animation.objects.empty() || !animation.camera.empty() ||
        !animation.lights.empty()) {
        out.scene.animation = std::move(animation);
        // Placed as every later moment will be (glTF parts were placed as at
        // time 0), so that the first frame is the same scene however it is
        // reached (spec §22).
        set_scene_time(out.scene, start_time, s.name);
    }
    return out;
}

}  // namespace sombra
