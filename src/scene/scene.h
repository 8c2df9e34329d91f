// The scene model of spec §2: the world the renderer works on, in world
// space. How to render it (image size, samples, integrator) is not part of
// it: render/render_settings.h, which a scene file's reader returns beside it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "scene/hdr_image.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/texture.h"

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

// Where a range of the world's triangles came from: one entry of the scene
// file's "objects" or one quad light (for messages and `sombra explain`).
struct SceneObject {
    std::string name;  // the scene file's JSON pointer ("/objects/2", "/lights/1"), or the model's file name
    std::string file;  // the mesh file (empty for a quad light)
    std::uint32_t first_triangle = 0;  // its triangles are first_triangle … first_triangle + triangle_count − 1
    std::uint32_t triangle_count = 0;
};

struct Scene {
    Vec3 background{0.0f};
    std::optional<EnvironmentMap> environment;  // when set, replaces `background`
    CameraSpec camera;
    std::vector<Material> materials;
    std::vector<Texture> textures;  // the materials' TextureRefs index this table (spec §12)
    std::vector<PunctualLight> lights;
    TriangleMesh geometry;             // all objects, world space; material_ids index materials
    std::vector<SceneObject> objects;  // in triangle order, covering geometry's triangles
};

// The object triangle `triangle` of scene.geometry belongs to (nullptr if none does).
const SceneObject* object_of_triangle(const Scene& scene, std::uint32_t triangle);

// True when the scene holds version-2 content that the direct integrator
// cannot light with (spec §10): quad lights (materials that emit from the
// front only), an environment map, or mirror or dielectric materials on some
// triangle. Emissive triangles of version 1 (ke, Ke) do not count.
bool needs_path_integrator(const Scene& scene);

}  // namespace sombra
