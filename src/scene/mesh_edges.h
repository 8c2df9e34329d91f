// Whether a mesh is closed: a medium's boundary (spec §26) must be, or rays
// leak in and out through its holes.
#pragma once

#include <cstddef>
#include <cstdint>

#include "scene/mesh.h"

namespace sombra {

// The edges of triangles first … first + count − 1 of `mesh` that belong to
// exactly one of them. Corners at equal positions count as one vertex (a
// seam that splits vertices for its texture coordinates is no hole), and
// triangles with two corners at one position are skipped. 0: closed.
std::size_t open_edge_count(const TriangleMesh& mesh, std::uint32_t first, std::uint32_t count);

}  // namespace sombra
