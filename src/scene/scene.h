// The loaded scene of spec §2: everything the renderer needs, in world space.
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

// Which estimator computes each sample (spec §10).
enum class IntegratorKind {
    Direct,  // point lights' direct light, emission and background seen (spec §4)
    Path,    // the whole rendering equation by path tracing
};

// How material textures are looked up (spec §12).
enum class TextureFilter {
    Bilinear,  // the default: bilinear at full resolution for every ray; supersampling antialiases
    Mipmap,    // trilinear in a mip pyramid at the level of the camera ray's cone footprint (render/ray_cone.h)
};

struct RenderSettings {
    int width = 640;
    int height = 480;
    int spp = 1;
    std::uint64_t seed = 0;
    IntegratorKind integrator = IntegratorKind::Direct;
    int max_depth = 8;  // path: the most scattering events on a path, 0 … kMaxDepth
    // Mipmap needs the textures' pyramids (build_mip_pyramids, scene/texture_mipmap.h)
    // built before rendering; without them lookups stay at full resolution.
    TextureFilter texture_filter = TextureFilter::Bilinear;
};

// Limits on what a render may ask for: anything beyond is a mistake, not a
// request (a 100000-pixel-wide image, a billion samples). The scene loader and
// the command-line overrides check against the same numbers.
inline constexpr int kMaxImageSide = 32768;
inline constexpr std::int64_t kMaxPixels = std::int64_t{1} << 28;
inline constexpr int kMaxSpp = 65536;
inline constexpr int kMaxDepth = 1024;

// "" when the settings lie within the limits above, else a short message
// naming the offending field, e.g. "width must be between 1 and 32768".
std::string render_settings_problem(const RenderSettings& r);

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
    std::string file;        // as written in the scene file (for messages)
    HdrImage image;          // finite, non-negative linear RGB
    float scale = 1;         // radiance = scale × texel, scale ≥ 0
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
    RenderSettings render;
    Vec3 background{0.0f};
    std::optional<EnvironmentMap> environment;  // when set, replaces `background`
    CameraSpec camera;
    std::vector<Material> materials;
    std::vector<Texture> textures;  // the materials' TextureRefs index this table (spec §12)
    std::vector<PunctualLight> lights;
    TriangleMesh geometry;  // all objects, world space; material_ids index materials
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
