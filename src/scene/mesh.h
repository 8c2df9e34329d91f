// Triangle meshes as structure-of-arrays vectors: what the loaders produce and,
// once transformed to world space and concatenated, what the acceleration
// structures and the integrator read.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/vec2.h"
#include "core/vec3.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/texture_refs.h"

namespace sombra {

using Index3 = std::array<std::uint32_t, 3>;

// Marks a triangle corner without a vertex normal.
inline constexpr std::uint32_t kNoNormal = 0xffffffffu;
// Marks a triangle corner without a texture coordinate (the renderer uses (0, 0)).
inline constexpr std::uint32_t kNoUv = 0xffffffffu;

struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Index3> triangles;  // corners, indices into positions

    // Vertex normals: either both empty (no normals anywhere), or
    // normal_indices.size() == triangles.size() with each entry an index into
    // normals or kNoNormal. A triangle is smooth-shaded only when all three
    // of its corners have a normal (spec §9).
    std::vector<Vec3> normals;
    std::vector<Index3> normal_indices;

    // Texture coordinates, as the file gives them (OBJ `vt`, PLY u v / s t /
    // texture_u texture_v; v = 0 is the image's bottom row), the same
    // convention as normals: either both empty, or uv_indices.size() ==
    // triangles.size() with each entry an index into uvs or kNoUv.
    std::vector<Vec2> uvs;
    std::vector<Index3> uv_indices;

    // One material index per triangle: into the loader's material list for a
    // loaded file, into Scene::materials for the scene's world geometry.
    std::vector<std::uint32_t> material_ids;

    std::size_t triangle_count() const { return triangles.size(); }
    bool has_normals() const { return !normal_indices.empty(); }
    bool has_uvs() const { return !uv_indices.empty(); }
};

// A pinhole camera that a model file places (glTF), in the file's
// coordinates: at `origin`, looking along `forward`, with `up` (both unit,
// perpendicular), a vertical field of view, and the image aspect (width /
// height) the file asks for, 0 when it leaves that to the image.
struct ModelCamera {
    Vec3 origin, forward, up;
    float yfov_degrees = 45;
    float aspect = 0;
};

// A mesh file as read from disk: geometry in the file's own coordinates and
// the materials its faces refer to. Loaders always leave at least one
// material when there are triangles (the default one for faces without).
// Materials' TextureRefs index `textures`, the file's own table.
struct LoadedMesh {
    TriangleMesh mesh;
    std::vector<Material> materials;
    std::vector<Texture> textures{};

    // What only glTF files carry (empty for OBJ and PLY): the point lights
    // and the first camera the file's scene places, in the file's
    // coordinates; and per material (parallel to `materials`, or empty) the
    // texture references the renderer does not apply yet.
    std::vector<PointLight> lights;
    std::optional<ModelCamera> camera;
    std::vector<GltfMaterialTextures> texture_refs;
};

}  // namespace sombra
