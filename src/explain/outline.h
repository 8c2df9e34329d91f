// The lines that draw a mesh as an outline: its boundary and crease edges,
// and its silhouette as seen along one direction. What explain's SVG shows
// of the scene: enough to recognise walls, boxes and a bunny, few enough
// lines for a browser.
#pragma once

#include <cstddef>
#include <vector>

#include "core/vec3.h"
#include "scene/mesh.h"

namespace sombra {

struct Segment {
    Vec3 a, b;
};

// Edges of `mesh` that belong to one triangle only (boundaries), to more
// than two, or to two whose normals differ by more than 35° (creases), and
// silhouette edges: one neighbour faces `view_dir`, the other away. At most
// `budget` of them, the longest first (as seen along view_dir). A mesh of
// more than `max_triangles` gets its bounding box instead: its edge list
// would cost more memory and time than the picture is worth.
std::vector<Segment> outline_segments(const TriangleMesh& mesh, Vec3 view_dir, std::size_t budget,
                                      std::size_t max_triangles = 4'000'000);

// The 12 edges of the bounding box of triangles [first, first + count).
std::vector<Segment> box_segments(const TriangleMesh& mesh, std::size_t first, std::size_t count);

}  // namespace sombra
