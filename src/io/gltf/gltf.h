// What the glTF 2.0 loader's parts share, private to src/io/gltf (spec §13):
// parsing with tinygltf behind guards (gltf_file.cpp) and the JSON types
// checked before it (gltf_json_types.cpp), reading accessors
// with every bound checked (gltf_accessors.cpp), decoding Draco-compressed
// primitives (gltf_draco.cpp) and EXT_meshopt_compression's buffer views
// (gltf_meshopt.cpp), materials and lights (gltf_materials.cpp);
// gltf_loader.cpp walks the node tree and assembles the LoadedMesh.
#pragma once

// tinygltf's configuration, the same in every translation unit that sees
// its classes (their default members depend on it): no stb_image in
// tinygltf (sombra's texture module decodes the images, gltf_textures.cpp),
// no external images read by tinygltf.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec2.h"
#include "core/vec3.h"
#include "io/gltf/texture_refs.h"
#include "io/mesh_file.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/texture.h"
#include "scene/transform.h"

namespace sombra::gltf {

// The extensions sombra reads. Any other listed in extensionsRequired is an
// error; in extensionsUsed, a warning.
inline constexpr const char* kDraco = "KHR_draco_mesh_compression";
inline constexpr const char* kQuantization = "KHR_mesh_quantization";
inline constexpr const char* kLights = "KHR_lights_punctual";
inline constexpr const char* kIor = "KHR_materials_ior";
inline constexpr const char* kEmissiveStrength = "KHR_materials_emissive_strength";
inline constexpr const char* kSpecular = "KHR_materials_specular";
inline constexpr const char* kTransmission = "KHR_materials_transmission";
inline constexpr const char* kVolume = "KHR_materials_volume";
inline constexpr const char* kClearcoat = "KHR_materials_clearcoat";
inline constexpr const char* kSheen = "KHR_materials_sheen";
inline constexpr const char* kUnlit = "KHR_materials_unlit";
inline constexpr const char* kTextureTransform = "KHR_texture_transform";
inline constexpr const char* kMeshopt = "EXT_meshopt_compression";
inline constexpr const char* kWebp = "EXT_texture_webp";
inline constexpr const char* kGpuInstancing = "EXT_mesh_gpu_instancing";

// Reads and parses a .gltf or .glb file with tinygltf, after the checks that
// keep hostile input away from it: the file's size, the GLB header and chunk
// layout, at most one buffer in the BIN chunk, external files only inside the
// file's folder and within a byte budget; images are not read; every
// member's JSON type (check_json_types), an unsupported extension in
// extensionsRequired named first. Then checks asset.version and
// extensionsRequired, and decodes EXT_meshopt_compression's buffer views
// (gltf_meshopt.h), so that accessors and images read them as any other. Throws Error(path, ...), or Error("PATH: /pointer", ...)
// for a member of the wrong type.
tinygltf::Model parse_file(const std::filesystem::path& path, Diagnostics& diag);

// Thrown for a feature that makes one primitive unusable but not the file
// (sparse accessors): the loader skips the primitive with one warning.
struct Unsupported {
    std::string feature;
};

// The vertex attributes and indices a primitive needs, by what they mean:
// which component types and counts each may have (glTF 2.0 §3.7.2.1, with
// KHR_mesh_quantization's additions when the file uses it).
// EXT_mesh_gpu_instancing's TRANSLATION and SCALE read as Position, its
// ROTATION (float or normalised signed integers) as Rotation. Animation
// samplers' inputs (SCALAR float) read as KeyTimes, their translation and
// scale outputs (VEC3 float) as KeyVector, rotations (VEC4 float or
// normalised integers) as KeyRotation.
enum class Semantic { Position, Normal, Tangent, Texcoord, Color, Rotation, KeyTimes, KeyVector, KeyRotation };

struct AccessorReader {
    const tinygltf::Model& model;
    std::string file;        // the path, for messages
    bool quantized = false;  // the file lists KHR_mesh_quantization in extensionsUsed
};

// Accessor `index` as `components` floats per element (3 for positions and
// normals, 2 for texture coordinates, 4 for tangents, 4 for colours: RGB
// colours get alpha 1), normalised integers converted as glTF says. Checks
// the index, the accessor's type and component type for `semantic`, and that
// every byte read lies inside its buffer view and buffer, with the alignment
// glTF requires. Throws Error(file, "accessor N (WHAT): ...") or Unsupported.
std::vector<float> read_floats(const AccessorReader& r, int index, Semantic semantic, const std::string& what);

// Accessor `index` as vertex indices (SCALAR, unsigned byte, short or int),
// each checked < vertex_count. Same checks and errors as read_floats.
std::vector<std::uint32_t> read_indices(const AccessorReader& r, int index, std::size_t vertex_count,
                                        const std::string& what);

// The bytes of buffer view `index`, checked: the view exists, names an
// existing buffer and lies inside it. Throws Error(file, "WHAT: bufferView N ...").
std::span<const unsigned char> buffer_view_bytes(const tinygltf::Model& model, int index, const std::string& file,
                                                 const std::string& what);

// "TEXCOORD_<set>".
inline std::string texcoord_name(unsigned set) { return "TEXCOORD_" + std::to_string(set); }

// The element count of accessor `index` (checked to exist), for Draco
// primitives, whose accessors have no data of their own.
std::size_t accessor_count(const AccessorReader& r, int index, const std::string& what);

// One triangle primitive in the file's coordinates, read and checked.
struct PrimitiveData {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // empty, or one per position
    std::vector<Vec2> uvs;      // empty, or one per position; sombra's convention (v = 0 at the bottom)
    std::array<std::vector<Vec2>, kUvSets - 1> extra_uvs;  // TEXCOORD_1, …: as uvs
    std::vector<VertexTangent> tangents;                   // empty, or one per position (TANGENT; not yet normalised)
    std::vector<Rgba> colors;                              // empty, or one per position (COLOR_0, clamped to [0, 1])
    std::vector<std::uint32_t> indices;                    // three per triangle, each < positions.size()
    int material = -1;                                     // index into the file's materials; -1: none
    std::size_t clamped_colors = 0;                        // colour components the file gave outside [0, 1]
};

// Mesh `index`'s primitives (the index checked by the caller), each read
// and checked, or nothing for one that is skipped (not triangles, sparse
// accessors): counted in `skipped` by what was skipped, with the features
// not drawn (more attribute sets, morph targets); colour components
// clamped add to `clamped_colors`. Throws Error for a broken primitive.
using Primitives = std::vector<std::optional<PrimitiveData>>;
Primitives read_mesh(const AccessorReader& r, int index, std::size_t material_count,
                     std::map<std::string, std::size_t>& skipped, std::size_t& clamped_colors);

// TANGENT as read (x, y, z, w per vertex) → tangents, the handedness the
// sign of w (glTF asks for ±1 exactly; its sign is what the frame needs).
std::vector<VertexTangent> tangents_of(const std::vector<float>& xyzw);
// COLOR_0 as read (RGBA per vertex) → colours clamped to [0, 1], counting
// the components clamped into `clamped`.
std::vector<Rgba> colors_of(const std::vector<float>& rgba, std::size_t& clamped);

// Decodes a KHR_draco_mesh_compression primitive with Draco: the
// extension's bufferView holds the compressed mesh, its "attributes" object
// maps POSITION, NORMAL, TEXCOORD_0 … 3, TANGENT and COLOR_0 to Draco attribute
// ids (those the primitive lists). Throws Error.
PrimitiveData decode_draco(const AccessorReader& r, const tinygltf::Primitive& primitive,
                           const tinygltf::Value& extension, const std::string& what);

// Every material of the file as sombra's `pbr` (spec §11), in file order,
// with its texture references as the file gives them (apply_textures
// turns them into texture slots).
struct Materials {
    std::vector<Material> materials;
    std::vector<GltfMaterialTextures> texture_refs;
};
Materials convert_materials(const tinygltf::Model& model, const std::string& file, Diagnostics& diag);

// Whether some texture of `refs` reads a TEXCOORD_k (1 ≤ k < kUvSets) that
// `p` does not have: as the Khronos sample viewer does, such a texture is
// treated as missing there, its parameter keeping its constant (spec §24).
bool lacks_texcoord(const PrimitiveData& p, const GltfMaterialTextures& refs);

// Decodes the images that `refs` (one per material) name and points each
// material's texture slots (scene/material.h) at them in `textures`: base
// colour (sRGB; its A channel the cut-out of MASK and BLEND materials),
// metallic-roughness (roughness from G, metallic from B), normal, emissive,
// KHR_materials_specular's specular (A) and specular colour (sRGB RGB),
// KHR_materials_transmission's transmission (R), KHR_materials_clearcoat's
// strength (R) and roughness (G), KHR_materials_sheen's colour (sRGB RGB)
// and roughness (A),
// with the samplers' wrap modes; occlusion is ignored (spec §13). Images come
// from buffer views (checked against their buffers), data: URIs, or files
// beside the model (a missing one is a warning and the constant is used; a
// path leaving the model's folder is an error). A KHR_texture_transform other
// than the identity becomes the slot's uv transform (uv_transform_of). Each
// slot reads the uv set of its reference's texCoord (its own or the
// extension's); one of kUvSets or more is not applied: the constant is
// used, with one warning. Throws Error(file, ...)
// for a broken image or a transform that overflows.
void apply_textures(const tinygltf::Model& model, const std::filesystem::path& path,
                    const std::vector<GltfMaterialTextures>& refs, std::vector<Material>& materials,
                    std::vector<Texture>& textures, Diagnostics& diag);

// KHR_texture_transform's offset, rotation (radians) and scale, which map
// glTF texture coordinates (v = 0 at the image's top), as the same map of
// sombra's stored coordinates (u, 1 − v): the transform a TextureRef applies.
UvTransform uv_transform_of(Vec2 offset, float rotation, Vec2 scale);

// The KHR_lights_punctual light `index` (spec §13, §16) at its node's
// origin, looking down its −z axis, in the node's own coordinates: point and
// spot lights with I = colour × intensity / 683 W/sr, directional lights with
// E = colour × intensity / 683 W/m². Other types give nothing, their name in
// `skipped_type`. Throws Error for a bad index, non-finite or negative
// values, or cone angles outside 0 ≤ inner, 0 < outer ≤ π/2; inner ≥ outer
// reads as inner = outer (with a warning unless they are equal).
std::optional<PunctualLight> punctual_light(const tinygltf::Model& model, int index, const std::string& file,
                                            std::string& skipped_type, Diagnostics& diag);

// The camera `index` placed by `world` (its scale ignored, as glTF says),
// or nothing (with a warning) when it is degenerate. znear and zfar are
// not used (nothing is clipped), for either kind. An orthographic camera's
// xmag is not used either: its half-width is ymag times the image's aspect
// (spec §24), and a ymag that is not a finite positive number is an error.
std::optional<ModelCamera> place_camera(const tinygltf::Model& model, int index, const Transform& world,
                                        const std::string& file, Diagnostics& diag);

// The KHR_lights_punctual light that node `node` (index `node_index`)
// carries, placed by the node's `world` transform, with `in_node` set to
// the light in the node's own coordinates; none when the node carries no
// light, or one of a type not rendered (counted in `skipped`). A light
// placed where it is not finite is an error naming the node.
std::optional<PunctualLight> place_light(const tinygltf::Model& model, const tinygltf::Node& node, int node_index,
                                         const Transform& world, const std::string& file, Diagnostics& diag,
                                         std::map<std::string, std::size_t>& skipped, PunctualLight& in_node);

// T · R · S (glTF 2.0 §3.5.3) for the quaternion (x, y, z, w), normalised
// here; nothing when its length is zero or not finite.
std::optional<Transform> trs_transform(Vec3 translation, double x, double y, double z, double w, Vec3 scale);

// The transforms EXT_mesh_gpu_instancing gives node `index` (its
// TRANSLATION · ROTATION · SCALE per instance, in the node's coordinates,
// applied before the node's own), in order; empty when it has none. Checks
// the attributes' accessors (types as the extension allows, counts equal,
// at most `room` instances, values finite), each rotation a non-zero
// quaternion and each scale non-zero, and that the node has a mesh. Throws
// Error(file, "node N: EXT_mesh_gpu_instancing: ...") or the accessor's error.
std::vector<Transform> gpu_instances(const AccessorReader& r, const tinygltf::Node& node, int index, std::size_t room);

// The file's animations (spec §22, glTF 2.0 §3.11), all of them on one
// clock: their translation, rotation and scale channels with their samplers
// read and checked. `order` lists the nodes the scene reaches, parents
// first. Channels of morph target weights, or without a node, are counted
// in `skipped`. Nothing when no channel animates a node. Throws
// Error(file, "animation A: channel C: ...") or ("... sampler S: ...").
std::shared_ptr<GltfNodeAnimation> read_animations(const AccessorReader& r, const std::vector<std::uint32_t>& order,
                                                   std::map<std::string, std::size_t>& skipped);

// Which nodes move (a channel targets them or an ancestor: 1) and every
// node's world transform at time 0; nothing moves without an animation.
struct Motion {
    std::vector<char> moving;
    std::vector<Transform> at_start;
};
Motion motion_of(const GltfNodeAnimation* animation, std::size_t node_count);

// A JSON number that must be an integer in [lo, hi] (tinygltf's own
// conversion of a huge double to int is undefined behaviour).
std::optional<int> value_int(const tinygltf::Value& v, int lo, int hi);

}  // namespace sombra::gltf
