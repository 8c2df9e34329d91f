// Polygon faces → LoadedMesh: what the OBJ and PLY loaders share once they
// have checked a face's indices: splitting polygons into triangles, dropping
// data that would poison the renderer (non-finite positions, unusable
// normals), the default material, and the "no triangles" error.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/mesh.h"
#include "scene/polygon_triangulate.h"

namespace sombra {

// The material index of a face that names none: it gets default_material().
inline constexpr std::uint32_t kNoMaterial = 0xffffffffu;

struct PolygonMeshBuilder {
    // `where` (the file's path) names the file in warnings and errors.
    explicit PolygonMeshBuilder(std::string where) : where_(std::move(where)) {}

    // The file's vertices and normals, in file order; the loader fills these.
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;

    // Faces with fewer than 3 corners that the loader saw but could not add.
    std::size_t skipped_small_faces = 0;

    void reserve_triangles(std::size_t count);

    // Adds one face: position indices < positions.size() (the loader checks
    // them, knowing where they came from); `normal_corners` empty when the
    // face has no normals, else one per corner, each < normals.size() or
    // kNoNormal; `material` an index into finish()'s list, or kNoMaterial.
    void add_face(std::span<const std::uint32_t> position_corners, std::span<const std::uint32_t> normal_corners,
                  std::uint32_t material);

    // The finished mesh. Normals are unit length; zero or non-finite ones are
    // removed (their corners get kNoNormal). Vertices with a non-finite
    // coordinate are removed with every triangle touching them (positions
    // then no longer match the file's numbering). When a face has no
    // material, default_material() is appended. Warnings go to `diag`.
    // Throws Error(where, "no triangles ...") when no triangle is left.
    LoadedMesh finish(std::vector<Material> materials, Diagnostics& diag);

private:
    void drop_non_finite_positions(Diagnostics& diag);
    void clean_normals(Diagnostics& diag);

    std::string where_;
    TriangleMesh mesh_;
    bool has_normals_ = false;
    std::size_t overlap_fans_ = 0;
    PolygonScratch scratch_;
    std::vector<Vec3> corner_positions_;
    std::vector<PolygonTriangle> split_;
};

}  // namespace sombra
