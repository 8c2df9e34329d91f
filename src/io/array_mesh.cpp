#include "io/array_mesh.h"

#include <array>

#include "io/mesh_builder.h"

namespace sombra {

LoadedMesh make_array_mesh(const std::string& where, std::vector<Vec3> positions,
                           std::span<const std::uint32_t> triangles, std::vector<Vec3> normals, std::vector<Vec2> uvs,
                           Diagnostics& diag) {
    const std::size_t n = positions.size();
    // An OBJ reader drops such vertices with a warning; arrays from code are refused, since a NaN there is a bug.
    for (std::size_t i = 0; i < n; ++i)
        if (!is_finite(positions[i]))
            throw Error(where, "positions[" + std::to_string(i) + "] is not finite (NaN or infinite)");
    if (!normals.empty() && normals.size() != n)
        throw Error(where, std::to_string(normals.size()) + " normals for " + std::to_string(n) +
                               " vertices: give one per vertex");
    if (!uvs.empty() && uvs.size() != n)
        throw Error(where,
                    std::to_string(uvs.size()) + " uvs for " + std::to_string(n) + " vertices: give one per vertex");
    if (triangles.size() % 3 != 0) throw Error(where, "the triangle indices are not a multiple of 3");
    for (std::size_t i = 0; i < triangles.size(); ++i)
        if (triangles[i] >= n)
            throw Error(where, "indices[" + std::to_string(i / 3) + "] refers to vertex " +
                                   std::to_string(triangles[i]) + ", past the " + std::to_string(n) + " vertices");

    MeshBuilder builder(where);
    builder.positions = std::move(positions);
    builder.normals = std::move(normals);
    builder.uvs = std::move(uvs);
    const bool has_normals = !builder.normals.empty(), has_uvs = !builder.uvs.empty();
    builder.reserve_triangles(triangles.size() / 3);
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
        const std::array<std::uint32_t, 3> corners{triangles[t], triangles[t + 1], triangles[t + 2]};
        builder.add_face(corners,
                         has_normals ? std::span<const std::uint32_t>(corners) : std::span<const std::uint32_t>(),
                         kNoMaterial,
                         has_uvs ? std::span<const std::uint32_t>(corners) : std::span<const std::uint32_t>());
    }
    return builder.finish({}, diag);
}

}  // namespace sombra
