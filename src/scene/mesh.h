// Triangle meshes as structure-of-arrays vectors: what the readers produce
// (io/mesh_file.h) and, once transformed to world space and concatenated,
// what the acceleration structures and the integrator read.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/vec2.h"
#include "core/vec3.h"
#include "scene/texture.h"

namespace sombra {

using Index3 = std::array<std::uint32_t, 3>;

// Marks a triangle corner without a vertex normal.
inline constexpr std::uint32_t kNoNormal = 0xffffffffu;
// Marks a triangle corner without a texture coordinate (the renderer uses (0, 0)).
inline constexpr std::uint32_t kNoUv = 0xffffffffu;
// Marks a triangle corner without a vertex tangent, and one without a vertex colour.
inline constexpr std::uint32_t kNoTangent = 0xffffffffu;
inline constexpr std::uint32_t kNoColor = 0xffffffffu;

// A vertex tangent (glTF TANGENT): a unit direction in the surface along
// which u increases, and the handedness that completes the normal map's
// frame: bitangent = handedness · (n × direction), toward increasing v in
// sombra's convention (spec §12). handedness is +1 or −1.
struct VertexTangent {
    Vec3 direction;
    float handedness = 1;
};

// Texture coordinate sets a mesh may carry (glTF TEXCOORD_0 … TEXCOORD_3;
// spec §24): TriangleMesh::uvs is set 0, extra_uvs the others.
inline constexpr unsigned kUvSets = 4;

// One texture coordinate set beyond the first: values and per-corner
// indices as TriangleMesh::uvs and uv_indices are (both empty, or one
// entry a triangle, each an index into uvs or kNoUv).
struct UvSet {
    std::vector<Vec2> uvs;
    std::vector<Index3> indices;
};

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
    // Sets 1 … kUvSets − 1: extra_uvs[k − 1] is set k. Only textures that
    // name their set read them (render/shading.cpp), so meshes without
    // (every OBJ and PLY, most glTF files) keep them empty and cost nothing.
    std::array<UvSet, kUvSets - 1> extra_uvs;

    // Vertex tangents (glTF TANGENT), the same convention: either both empty,
    // or tangent_indices.size() == triangles.size() with each entry an index
    // into tangents or kNoTangent. A normal map uses them where all three
    // corners have one, else the triangle's uv parameterisation (spec §12).
    // In world space (once assembled) as positions are.
    std::vector<VertexTangent> tangents;
    std::vector<Index3> tangent_indices;

    // Vertex colours (glTF COLOR_0), linear RGBA in [0, 1] (alpha 1 where the
    // file gives RGB), the same convention: either both empty, or
    // color_indices.size() == triangles.size() with each entry an index into
    // colors or kNoColor. RGB multiplies a pbr material's base colour where
    // all three corners have one (render/shading.h); alpha is kept for the
    // cut-outs, which multiply it into the material's alpha (spec §13).
    std::vector<Rgba> colors;
    std::vector<Index3> color_indices;

    // One material index per triangle: into the loader's material list for a
    // loaded file, into Scene::materials for the scene's world geometry.
    std::vector<std::uint32_t> material_ids;

    // Derived from normal_indices and uv_indices by mark_complete_corners
    // (corner_attributes.h; scene loading does it for the world geometry):
    // bit t % 64 of word t / 64 is set when all three corners of triangle t
    // have a normal (complete_normals: the triangle is smooth-shaded) or a uv
    // (complete_uvs). Shading tests these bits, an eighth of a megabyte each
    // for a million triangles, before it reads the triangle's entries of
    // normal_indices and uv_indices, 12 MB each, at random; a scene mixing
    // meshes with and without normals or uvs would otherwise read both on
    // every hit for nothing. Empty: not derived, and the indices are read.
    std::vector<std::uint64_t> complete_normals;
    std::vector<std::uint64_t> complete_uvs;

    std::size_t triangle_count() const { return triangles.size(); }
    bool has_normals() const { return !normal_indices.empty(); }
    bool has_uvs() const { return !uv_indices.empty(); }
    bool has_tangents() const { return !tangent_indices.empty(); }
    bool has_colors() const { return !color_indices.empty(); }
};

// False when `bits` (TriangleMesh::complete_normals or complete_uvs) says
// that some corner of `triangle` lacks the attribute; true when it says
// otherwise or was not derived.
inline bool may_be_complete(const std::vector<std::uint64_t>& bits, std::uint32_t triangle) {
    return bits.empty() || (bits[triangle / 64] >> (triangle % 64) & 1u) != 0;
}

// True when all three corners of `triangle` have a vertex normal: the
// triangle is smooth-shaded (spec §9).
inline bool has_vertex_normals(const TriangleMesh& mesh, std::uint32_t triangle) {
    if (!mesh.has_normals() || !may_be_complete(mesh.complete_normals, triangle)) return false;
    const Index3& n = mesh.normal_indices[triangle];
    return n[0] != kNoNormal && n[1] != kNoNormal && n[2] != kNoNormal;
}

// The corners of `triangle`, in its order.
inline std::array<Vec3, 3> triangle_corners(const TriangleMesh& mesh, std::uint32_t triangle) {
    const Index3& p = mesh.triangles[triangle];
    return {mesh.positions[p[0]], mesh.positions[p[1]], mesh.positions[p[2]]};
}

// The barycentric weights (b1, b2) of point y in the plane of `triangle`,
// from the areas it spans with the edges (for points sampled on a triangle
// rather than hit); false for a triangle of no area.
inline bool point_barycentrics(const TriangleMesh& mesh, std::uint32_t triangle, Vec3 y, float& b1, float& b2) {
    const auto [p0, p1, p2] = triangle_corners(mesh, triangle);
    const Vec3 e1 = p1 - p0, e2 = p2 - p0, d = y - p0;
    const float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    const float d1 = dot(d, e1), d2 = dot(d, e2);
    const float den = d11 * d22 - d12 * d12;
    if (!(den > 0.0f) || !std::isfinite(den)) return false;
    b1 = (d22 * d1 - d12 * d2) / den;
    b2 = (d11 * d2 - d12 * d1) / den;
    return true;
}

// The texture coordinates at barycentric weights (b1, b2) of `triangle`
// (the first corner weighs 1 − b1 − b2), or false, leaving `uv` untouched,
// when some corner has none. Every uv lookup goes through here.
inline bool interpolate_uv(const TriangleMesh& mesh, std::uint32_t triangle, float b1, float b2, Vec2& uv) {
    if (!mesh.has_uvs() || !may_be_complete(mesh.complete_uvs, triangle)) return false;
    const Index3& ti = mesh.uv_indices[triangle];
    if (ti[0] == kNoUv || ti[1] == kNoUv || ti[2] == kNoUv) return false;
    const Vec2 t0 = mesh.uvs[ti[0]], t1 = mesh.uvs[ti[1]], t2 = mesh.uvs[ti[2]];
    const float b0 = 1.0f - b1 - b2;
    uv = {b0 * t0.x + b1 * t1.x + b2 * t2.x, b0 * t0.y + b1 * t1.y + b2 * t2.y};
    return true;
}

// The texture coordinates of set `set` (< kUvSets) at `triangle`'s corners,
// or false when some corner has none (set 0: mesh.uvs, else extra_uvs).
inline bool uv_set_corners(const TriangleMesh& mesh, unsigned set, std::uint32_t triangle, Vec2 (&corners)[3]) {
    const std::vector<Vec2>& uvs = set == 0 ? mesh.uvs : mesh.extra_uvs[set - 1].uvs;
    const std::vector<Index3>& indices = set == 0 ? mesh.uv_indices : mesh.extra_uvs[set - 1].indices;
    if (indices.empty() || (set == 0 && !may_be_complete(mesh.complete_uvs, triangle))) return false;
    const Index3& ti = indices[triangle];
    if (ti[0] == kNoUv || ti[1] == kNoUv || ti[2] == kNoUv) return false;
    for (int k = 0; k < 3; ++k) corners[k] = uvs[ti[k]];
    return true;
}

// interpolate_uv for set `set` (< kUvSets; 0 is interpolate_uv itself).
inline bool interpolate_uv_set(const TriangleMesh& mesh, unsigned set, std::uint32_t triangle, float b1, float b2,
                               Vec2& uv) {
    if (set == 0) return interpolate_uv(mesh, triangle, b1, b2, uv);
    Vec2 t[3];
    if (!uv_set_corners(mesh, set, triangle, t)) return false;
    const float b0 = 1.0f - b1 - b2;
    uv = {b0 * t[0].x + b1 * t[1].x + b2 * t[2].x, b0 * t[0].y + b1 * t[1].y + b2 * t[2].y};
    return true;
}

// True when all three corners of `triangle` have a vertex colour (glTF COLOR_0).
inline bool has_vertex_colors(const TriangleMesh& mesh, std::uint32_t triangle) {
    if (!mesh.has_colors()) return false;
    const Index3& ci = mesh.color_indices[triangle];
    return ci[0] != kNoColor && ci[1] != kNoColor && ci[2] != kNoColor;
}

// The vertex colour at barycentric weights (b1, b2) of `triangle`, or false,
// leaving `color` untouched, when some corner has none.
inline bool interpolate_color(const TriangleMesh& mesh, std::uint32_t triangle, float b1, float b2, Rgba& color) {
    if (!has_vertex_colors(mesh, triangle)) return false;
    const Index3& ci = mesh.color_indices[triangle];
    const Rgba &c0 = mesh.colors[ci[0]], &c1 = mesh.colors[ci[1]], &c2 = mesh.colors[ci[2]];
    const float b0 = 1.0f - b1 - b2;
    for (std::size_t k = 0; k < 4; ++k) color[k] = b0 * c0[k] + b1 * c1[k] + b2 * c2[k];
    return true;
}

// The tangent at barycentric weights (b1, b2) of `triangle`: the blend of
// its corners' directions (not normalised: a caller orthonormalises it
// against its shading normal) and the handedness the weights favour; false,
// leaving both untouched, when some corner has none.
inline bool interpolate_tangent(const TriangleMesh& mesh, std::uint32_t triangle, float b1, float b2, Vec3& direction,
                                float& handedness) {
    if (!mesh.has_tangents()) return false;
    const Index3& ti = mesh.tangent_indices[triangle];
    if (ti[0] == kNoTangent || ti[1] == kNoTangent || ti[2] == kNoTangent) return false;
    const VertexTangent &t0 = mesh.tangents[ti[0]], &t1 = mesh.tangents[ti[1]], &t2 = mesh.tangents[ti[2]];
    const float b0 = 1.0f - b1 - b2;
    direction = b0 * t0.direction + b1 * t1.direction + b2 * t2.direction;
    handedness = b0 * t0.handedness + b1 * t1.handedness + b2 * t2.handedness < 0.0f ? -1.0f : 1.0f;
    return true;
}

}  // namespace sombra
