// What the OBJ and PLY loaders share, private to src/io: reading the
// file whole with the file-level errors both report the same way; splitting
// one polygon into triangles; and MeshBuilder, which turns checked faces
// into a LoadedMesh, dropping data that would poison the renderer
// (non-finite positions, unusable normals), adding the default material,
// and reporting "no triangles".
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec3.h"
#include "io/mesh_file.h"
#include "scene/mesh.h"

namespace sombra {

// The file's bytes. Throws Error(path, "no such file"), Error(path, "is a
// folder, not a mesh file"), or Error(path, ...) when it cannot be read.
std::string read_mesh_file(const std::filesystem::path& path);

// A mesh file opened after read_mesh_file's checks (with its errors), for a
// loader that reads it piece by piece; `size_on_disk` as it was when opened
// (0 when unknown).
struct OpenMeshFile {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file;
    std::uint64_t size_on_disk = 0;
};
OpenMeshFile open_mesh_file(const std::filesystem::path& path);

// Appends the rest of `file` (named `where` in errors) to `bytes`, to its
// end whatever its size on disk said.
void read_rest_of_file(std::FILE* file, const std::string& where, std::string& bytes);

// Corner numbers (0 … n-1 within one polygon) of one output triangle.
using PolygonTriangle = std::array<std::uint32_t, 3>;

// How a polygon was split.
enum class PolygonSplit {
    Fan,         // (0,1,2), (0,2,3), …: triangles, quads, convex or star-shaped polygons
    EarClipped,  // the fan would overlap: ear clipping in the Newell plane
    OverlapFan,  // the fan overlaps but the polygon is too large to clip: fan kept
};

// Scratch memory reused across polygons, so that splitting allocates only
// while the largest polygon seen so far grows.
struct PolygonScratch {
    std::vector<double> u, v;  // corners projected onto the best-fit plane
    std::vector<std::uint32_t> prev, next;
};

// Polygons with more corners than this are never ear-clipped (clipping is
// quadratic or worse in the corner count): a fan is kept and reported.
inline constexpr std::size_t kMaxEarClipCorners = 256;

// Appends exactly corners.size() - 2 triangles to `out` (nothing when fewer
// than 3 corners), each wound like the polygon. Non-finite corners give a fan.
PolygonSplit triangulate_polygon(std::span<const Vec3> corners, PolygonScratch& scratch,
                                 std::vector<PolygonTriangle>& out);

// The material index of a face that names none: it gets default_material().
inline constexpr std::uint32_t kNoMaterial = 0xffffffffu;

struct MeshBuilder {
    // `where` (the file's path) names the file in warnings and errors.
    explicit MeshBuilder(std::string where) : where_(std::move(where)) {}

    // The file's vertices and normals, in file order; the loader fills these.
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<Vec2> uvs;                                 // texture coordinates, in file order
    std::array<std::vector<Vec2>, kUvSets - 1> extra_uvs;  // sets 1, 2, …: glTF only, like the rest
    std::vector<VertexTangent> tangents;                   // glTF only, like the rest
    std::vector<Rgba> colors;                              // glTF only, like the rest

    // Faces with fewer than 3 corners that the loader saw but could not add.
    std::size_t skipped_small_faces = 0;

    void reserve_triangles(std::size_t count);

    // Adds one face: position indices < positions.size() (the loader checks
    // them, knowing where they came from); `normal_corners` empty when the
    // face has no normals, else one per corner, each < normals.size() or
    // kNoNormal; `material` an index into finish()'s list, or kNoMaterial.
    // `uv_corners`, `tangent_corners` and `color_corners` likewise: empty, or
    // one per corner, < uvs.size() (tangents, colors) or kNoUv (kNoTangent,
    // kNoColor); extra_uv_corners[k − 1] for set k (< extra_uvs[k − 1].size()).
    using ExtraUvCorners = std::array<std::span<const std::uint32_t>, kUvSets - 1>;
    void add_face(std::span<const std::uint32_t> position_corners, std::span<const std::uint32_t> normal_corners,
                  std::uint32_t material, std::span<const std::uint32_t> uv_corners = {},
                  std::span<const std::uint32_t> tangent_corners = {},
                  std::span<const std::uint32_t> color_corners = {}, const ExtraUvCorners& extra_uv_corners = {});

    // The finished mesh. Normals and tangent directions are unit length; zero
    // or non-finite ones are removed (their corners get kNoNormal, kNoTangent).
    // Vertices with a non-finite
    // coordinate are removed with every triangle touching them (positions
    // then no longer match the file's numbering). When a face has no
    // material, default_material() is appended. Warnings go to `diag`.
    // Throws Error(where, "no triangles ...") when no triangle is left.
    LoadedMesh finish(std::vector<Material> materials, Diagnostics& diag);
    // finish()'s mesh for a list of `material_count` materials kept by the
    // caller (a glTF file's meshes share one list): material ids past it
    // become material_count, and `uses_default` is set when any does.
    TriangleMesh finish_mesh(std::size_t material_count, bool& uses_default, Diagnostics& diag);

    // Triangles added so far.
    std::size_t triangle_count() const { return mesh_.triangles.size(); }

private:
    void drop_non_finite_positions(Diagnostics& diag);
    void clean_directions(Diagnostics& diag);

    std::string where_;
    TriangleMesh mesh_;
    bool has_normals_ = false;
    bool has_uvs_ = false;
    std::array<bool, kUvSets - 1> has_extra_uvs_{};
    bool has_tangents_ = false;
    bool has_colors_ = false;
    std::size_t overlap_fans_ = 0;
    PolygonScratch scratch_;
    std::vector<Vec3> corner_positions_;
    std::vector<PolygonTriangle> split_;
};

}  // namespace sombra
