// The scene model of spec §2: the world the renderer works on, in world
// space. How to render it (image size, samples, integrator) is not part of
// it: render/render_settings.h, which a scene file's reader returns beside it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "scene/animation.h"
#include "scene/hdr_image.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/medium.h"
#include "scene/mesh.h"
#include "scene/texture.h"
#include "scene/transform.h"

namespace sombra {

// The camera as written in the scene file (spec §3): exactly one form is set.
struct CameraBasis {
    Vec3 origin, left, up, forward;
};
struct CameraLookAt {
    Vec3 origin, look_at;
    Vec3 up{0, 1, 0};
    float fov_degrees = 45;
};
struct CameraSpec {
    std::optional<CameraBasis> basis;
    std::optional<CameraLookAt> look_at;
    // A thin lens (spec §17) on either form: 0 is the pinhole. The focus
    // plane lies focus_distance along the unit forward axis; unset, it is
    // |look_at − origin| (look-at form; required with the basis form when
    // aperture_radius > 0).
    float aperture_radius = 0;
    std::optional<float> focus_distance;
    // An orthographic camera (a glTF file's, spec §24): parallel rays along
    // the forward axis, leaving the plane through the origin across it; the
    // view's half-height is ortho_half_height, its half-width that times the
    // image aspect (W/H). The look-at form's fov and the lens are unused.
    // Scene files have only perspective cameras.
    enum class Projection : std::uint8_t { Perspective, Orthographic };
    Projection projection = Projection::Perspective;
    float ortho_half_height = 1;
};

// An equirectangular environment map (spec §10 "environment"): it replaces
// the background, is seen by rays that leave the scene and, under the path
// integrator, lights it.
struct EnvironmentMap {
    std::string file;  // as written in the scene file (for messages)
    HdrImage image;    // finite, non-negative linear RGB
    float scale = 1;   // radiance = scale × texel, scale ≥ 0
    float rotate_y_degrees = 0;
};

// Where a range of the world's triangles, or of the instances, came from:
// one entry of the scene file's "objects" or one quad light (for messages
// and `sombra explain`).
struct SceneObject {
    std::string name;  // the scene file's JSON pointer ("/objects/2", "/lights/1"), or the model's file name
    std::string file;  // the mesh file (empty for a quad light)
    std::uint32_t first_triangle = 0;  // its triangles are first_triangle … first_triangle + triangle_count − 1
    std::uint32_t triangle_count = 0;
    // An instanced object (spec §23) draws its meshes as instances
    // first_instance … first_instance + instance_count − 1 instead.
    std::uint32_t first_instance = 0;
    std::uint32_t instance_count = 0;
    // A medium boundary (spec §26): `interior` fills the side its winding
    // normals point away from, `exterior` the other side (kNoMedium:
    // vacuum). Without bounds_medium a crossing keeps the current medium.
    bool bounds_medium = false;
    std::uint32_t interior = kNoMedium;
    std::uint32_t exterior = kNoMedium;
};

// Scene::interface_material when no object is an "interface" (spec §26).
inline constexpr std::uint32_t kNoInterface = 0xffffffffu;

// Marks "not in an instance": a triangle of Scene::geometry.
inline constexpr std::uint32_t kNoInstance = 0xffffffffu;

// One drawing of an instanced mesh (spec §23): the mesh stays in its own
// coordinates, stored once however often it is drawn. The builder derives
// the inverse, the normals' matrix and the mirroring from object_to_world.
struct Instance {
    std::uint32_t mesh = 0;    // index into Scene::instanced_meshes
    std::uint32_t object = 0;  // index into Scene::objects
    Transform object_to_world;
    Transform world_to_object;
    Transform normal_to_world;  // the inverse transpose of object_to_world's linear part
    // A negative determinant: the winding flips (spec §11), as the builder's
    // flattened copies swap two corners.
    bool mirrored = false;
    // The medium inside this drawing when its object bounds one (spec §26):
    // the object's interior, or for a grid, this drawing's own placement of it.
    std::uint32_t interior = kNoMedium;
};

struct Scene {
    Vec3 background{0.0f};
    std::optional<EnvironmentMap> environment;  // when set, replaces `background`
    CameraSpec camera;
    std::vector<Material> materials;
    std::vector<Texture> textures;  // the materials' TextureRefs index this table (spec §12)
    std::vector<PunctualLight> lights;
    TriangleMesh geometry;             // all objects drawn once, world space; material_ids index materials
    std::vector<SceneObject> objects;  // in triangle order, covering geometry's triangles
    // Meshes drawn several times (spec §23), each in its own coordinates
    // with material_ids into materials, and their drawings.
    std::vector<TriangleMesh> instanced_meshes;
    std::vector<Instance> instances;
    // Keyframes (spec §22); the rest of the scene is at the moment
    // set_scene_time (scene/animation.h) last moved it to.
    std::optional<SceneAnimation> animation;
    // Participating media (spec §26) and the one that fills the space
    // outside every object, where the camera starts (kNoMedium: vacuum).
    std::vector<Medium> media;
    std::uint32_t render_medium = kNoMedium;
    // Where the camera starts when it sits inside an object's interior
    // ("camera": {"medium"}); unset: the render medium.
    std::optional<std::uint32_t> camera_medium;
    // The index in `materials` of the "interface" material (MaterialType::
    // Interface), or kNoInterface when no object uses it.
    std::uint32_t interface_material = kNoInterface;
};

// True when some medium fills space: the render's, the camera's or an
// object's interior (spec §26).
bool uses_media(const Scene& scene);

// The medium a camera ray starts in.
inline std::uint32_t starting_medium(const Scene& scene) { return scene.camera_medium.value_or(scene.render_medium); }

// Places `instance` by `object_to_world`, deriving its inverse, normals'
// matrix and mirroring; false (the instance untouched) when the matrix is
// not invertible in float.
bool place_instance(Instance& instance, const Transform& object_to_world);

// Places a grid medium (spec §26) by its grid's index-to-world transform,
// then `object_to_world`; false (the medium untouched) when together they
// are not invertible in float.
bool place_grid_medium(Medium& medium, const Transform& object_to_world);

// The mesh a triangle index belongs to: Scene::geometry for kNoInstance,
// else the instance's mesh.
inline const TriangleMesh& surface_mesh(const Scene& scene, std::uint32_t instance) {
    return instance == kNoInstance ? scene.geometry : scene.instanced_meshes[scene.instances[instance].mesh];
}

// The object a hit on `triangle` of surface_mesh(scene, instance) belongs to
// (nullptr if none does).
const SceneObject* object_of_surface(const Scene& scene, std::uint32_t triangle, std::uint32_t instance);

// Triangles stored (the world geometry and each instanced mesh once) and
// drawn (each instance's mesh once per instance): spec §23's statistics.
std::uint64_t stored_triangle_count(const Scene& scene);
std::uint64_t drawn_triangle_count(const Scene& scene);

// The object triangle `triangle` of scene.geometry belongs to (nullptr if none does).
const SceneObject* object_of_triangle(const Scene& scene, std::uint32_t triangle);

// True when the scene holds version-2 content that the direct integrator
// cannot light with (spec §10): quad lights (materials that emit from the
// front only), an environment map, or mirror or dielectric materials on some
// triangle. Emissive triangles of version 1 (ke, Ke) do not count.
bool needs_path_integrator(const Scene& scene);

// True when something in the scene emits light (spec §27): a light of some
// power, an emissive material on some triangle, an emitting medium, a
// background or environment that is not black.
bool emits_light(const Scene& scene);

}  // namespace sombra
