// Private to the scene loader: parsing a scene file's JSON text, reading
// typed values out of it, and reading its sections (spec §2, §3, §5, §8,
// §10, §11), each validated on its own. Every failure names its place as
// "scene.json:line:col" (syntax) or "scene.json: /json/pointer" (meaning).
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/vec3.h"
#include "core/vec3d.h"
#include "io/mesh_file.h"
#include "render/render_settings.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "scene/transform.h"

namespace sombra {

// Relative tolerance for "perpendicular" (spec §3: |cos| of the angle) and,
// in the same spirit, for "parallel" (sine of the angle): the camera's
// vectors and a quad light's edges are held to it.
inline constexpr double kAngleTolerance = 1e-3;

// True when a and b (non-zero) are parallel within kAngleTolerance.
inline bool nearly_parallel(Vec3d a, Vec3d b) { return length(cross(a, b)) <= kAngleTolerance * length(a) * length(b); }

using Json = nlohmann::json;

// The scene file being read: its name prefixes every WHERE.
struct SceneJson {
    std::string name;
    Diagnostics& diag;
};

// Parses JSON text. Throws Error("name:line:col", ...) for a syntax error (line
// and column 1-based, counted in bytes), and Error("name: /pointer", ...) for a
// duplicate key or nesting too deep to be a scene.
Json parse_scene_json(const std::string& text, const std::string& name);

// WHERE for the value at a JSON pointer ("" is the whole document).
std::string json_where(const SceneJson& s, std::string_view pointer);
[[noreturn]] void json_fail(const SceneJson& s, std::string_view pointer, const std::string& what);
void json_warn(const SceneJson& s, std::string_view pointer, const std::string& what);

// The pointer of a member or element below `pointer` (RFC 6901 escaping).
std::string json_child(std::string_view pointer, std::string_view key);
// "(looked for /abs/path, relative to the scene's folder)": where a file
// named in the scene was sought, for the message that it is missing.
std::string looked_for(const std::filesystem::path& path);
std::string json_child(std::string_view pointer, std::size_t index);

// Fails with "expected an object" (or an array) unless v is one.
void expect_object(const SceneJson& s, const Json& v, std::string_view pointer);
void expect_array(const SceneJson& s, const Json& v, std::string_view pointer);
// Fails with "unknown key 'k'" (WHERE naming the key) for any member not listed.
void expect_keys(const SceneJson& s, const Json& object, std::string_view pointer,
                 std::initializer_list<std::string_view> allowed);
// The member `key` of an object, or nullptr when absent.
const Json* find_member(const Json& object, std::string_view key);
// The member `key`; fails with "missing required key 'key'" when absent.
const Json& require_member(const SceneJson& s, const Json& object, std::string_view pointer, std::string_view key);

// A finite number that fits a float; fails with "expected a number".
float read_float(const SceneJson& s, const Json& v, std::string_view pointer);
// An integer in [lo, hi]; fails with "expected an integer" or "must be between lo and hi".
std::int64_t read_integer(const SceneJson& s, const Json& v, std::string_view pointer, std::int64_t lo,
                          std::int64_t hi);
// A non-negative integer of up to 64 bits.
std::uint64_t read_unsigned(const SceneJson& s, const Json& v, std::string_view pointer);
// [x, y, z] of finite numbers; fails with "expected an array of 3 numbers".
Vec3 read_vec3(const SceneJson& s, const Json& v, std::string_view pointer);
// An RGB triple with every component >= 0.
Vec3 read_rgb(const SceneJson& s, const Json& v, std::string_view pointer);
const std::string& read_string(const SceneJson& s, const Json& v, std::string_view pointer);

// "render": {width, height, spp, seed, integrator ("direct" | "path"),
// max_depth (0 … kMaxDepth)}; absent members keep their defaults.
RenderSettings read_render(const SceneJson& s, const Json& v, std::string_view pointer);

// "camera": exactly one of the basis form (origin, left, up, forward: non-zero,
// mutually perpendicular) and the look-at form (origin, look_at, up, fov).
CameraSpec read_camera(const SceneJson& s, const Json& v, std::string_view pointer);

// Where a scene file's textures come from and go: image files relative to
// `folder`, decoded into `*table` (Scene::textures), each file once per encoding.
struct SceneTextures {
    std::filesystem::path folder;
    std::vector<Texture>* table = nullptr;
};

// "materials": {name: {type, kd, ks, shininess, ke, ..., normal_map, alpha}},
// in name order. Warns when kd + ks exceeds 1 in a channel (not energy
// conserving). Textures (spec §12) are read into `textures`.
std::vector<Material> read_materials(const SceneJson& s, const Json& v, std::string_view pointer,
                                     SceneTextures& textures);

// Material member `key`, a parameter of kRgbTextureSlots or
// kScalarTextureSlots (scene/material.h): a constant ([r, g, b], each in
// [0, 1] for reflectances, >= 0 for ke; a number in [0, 1]) or a texture
// ({"texture": file, "scale": [r, g, b]}; {"texture": file, "channel":
// "r"|"g"|"b"|"a", "scale": s}), whose scale becomes the constant. Absent:
// unchanged, or "missing required key" when `required`.
void read_texturable(const SceneJson& s, const Json& material, std::string_view pointer, std::string_view key,
                     bool required, Material& m, SceneTextures& textures);

// "normal_map": file and "alpha": {"texture": file, "cutoff": c in [0, 1]},
// which any material may have (an alpha turns its cut-out test on); then
// sets m.textured.
void read_material_maps(const SceneJson& s, const Json& material, std::string_view pointer, Material& m,
                        SceneTextures& textures);

// A quad light (spec §10) as written: the parallelogram corner, corner +
// edge1, corner + edge1 + edge2, corner + edge2, emitting `radiance` toward
// the side edge1 × edge2 points to.
struct QuadLight {
    std::string pointer;  // "/lights/2", for messages
    Vec3 corner, edge1, edge2;
    Vec3 radiance;  // finite, each component >= 0
};

struct SceneLights {
    std::vector<PunctualLight> punctual;  // point, spot and directional lights, in file order
    std::vector<QuadLight> quads;
};

// "lights": [{type: "point" (the default when left out), position, intensity}
// | {type: "spot", position, direction, intensity, outer_angle, inner_angle}
// | {type: "directional", direction, irradiance}
// | {type: "quad", corner, edge1, edge2, radiance}] (scene_json_lights.cpp).
// A zero direction, spot angles outside 0 ≤ inner ≤ outer ≤ 90 (outer > 0),
// and zero or parallel quad edges are errors.
SceneLights read_lights(const SceneJson& s, const Json& v, std::string_view pointer);
QuadLight read_quad_light(const SceneJson& s, const Json& v, std::string_view pointer);

// The two triangles of a quad light, (p, p+a, p+a+b) and (p, p+a+b, p+b), as
// a loaded mesh with one material: diffuse kd = 0, ke = radiance, emitting
// from the front only. No normals, no texture coordinates.
LoadedMesh make_quad_light_mesh(const QuadLight& quad);

// "environment": {file, scale, rotate_y, clamp_negative}: the map read with
// read_hdr_image, its file relative to `folder`. clamp_negative (a sombra
// extension, default false) reads negative values as 0 with one warning.
EnvironmentMap read_environment(const SceneJson& s, const Json& v, std::string_view pointer,
                                const std::filesystem::path& folder);

// "media" (spec §26): {"NAME": {"type": "homogeneous", "sigma_a", "sigma_s",
// "g", "emission", "scale"}, …}. Coefficients are
// non-negative and come scaled; |g| < 1. In name order.
std::vector<Medium> read_media(const SceneJson& s, const Json& v, std::string_view pointer);

// The scene's "media", the render's medium ("render": {"medium"}) and the
// camera's ("camera": {"medium"}), into `builder`.
void read_scene_media(const SceneJson& s, const Json& root, SceneBuilder& builder);

// An object's "interior" and "exterior" (default: the render's medium) as
// indices into `media`; nothing when it has neither.
std::optional<MediumBoundary> read_object_media(const SceneJson& s, const Json& v, std::string_view pointer,
                                                const std::vector<Medium>& media, std::uint32_t render_medium);

// One warning for each object bounding a medium whose material lets no
// light in, whose glTF volume attenuation its interior replaces, or whose
// surface is not closed (spec §26).
void check_medium_objects(const SceneJson& s, const Scene& scene);

// "transform": a list of steps, the first listed acting first. The result is
// finite and invertible.
Transform read_transform(const SceneJson& s, const Json& v, std::string_view pointer);

// Spec §22: "animation": {"fps", "frames": [first, last]} (defaults 24 and
// [0, 0]); a keyed "transform" {"keys": [{"time", "transform"}, …]}; a keyed
// "camera" {"keys": [{"time", look-at camera keys…}, …]}. Times increase.
struct SceneClock {
    double fps = 24;
    std::int64_t first_frame = 0, last_frame = 0;
};
SceneClock read_animation(const SceneJson& s, const Json& v, std::string_view pointer);
std::vector<TransformKey> read_transform_keys(const SceneJson& s, const Json& v, std::string_view pointer);
std::vector<CameraKey> read_camera_keys(const SceneJson& s, const Json& v, std::string_view pointer);

}  // namespace sombra
