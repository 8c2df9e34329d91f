// A mesh handed over as arrays (the Python module's Scene.add_mesh, spec §19)
// rather than read from a file: assembled by the same MeshBuilder the OBJ
// reader feeds, so that the same numbers render the same as an OBJ file.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec2.h"
#include "core/vec3.h"
#include "io/mesh_file.h"

namespace sombra {

// The mesh of `triangles` (corner indices into `positions`), with per-vertex
// `normals` and `uvs` (each empty, or one per position; a corner's normal
// and uv are its vertex's), every face naming no material (it gets
// default_material(), as an OBJ file without `usemtl`). Throws
// Error(where, ...) for a non-finite position, a corner index past the
// vertices, a normals or uvs count that is not the vertices', or no triangle.
LoadedMesh make_array_mesh(const std::string& where, std::vector<Vec3> positions,
                           std::span<const std::uint32_t> triangles, std::vector<Vec3> normals, std::vector<Vec2> uvs,
                           Diagnostics& diag);

}  // namespace sombra
