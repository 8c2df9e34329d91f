#include "scene/mesh_edges.h"

#include <gtest/gtest.h>

namespace sombra {
namespace {

// A unit cube of 12 triangles over 8 shared corners.
TriangleMesh cube() {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(
            Vec3{static_cast<float>(i & 1), static_cast<float>(i >> 1 & 1), static_cast<float>(i >> 2 & 1)});
    const Index3 faces[12] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                              {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    m.triangles.assign(std::begin(faces), std::end(faces));
    return m;
}

TEST(MeshEdges, ClosedCubeHasNoOpenEdge) {
    const TriangleMesh m = cube();
    EXPECT_EQ(open_edge_count(m, 0, 12), 0u);
}

TEST(MeshEdges, RemovingOneFaceOpensItsFourBorderEdges) {
    const TriangleMesh m = cube();
    // Triangles 2 … 11: the face of the first two is missing.
    EXPECT_EQ(open_edge_count(m, 2, 10), 4u);
}

TEST(MeshEdges, VerticesSplitAtASeamAreWelded) {
    TriangleMesh m = cube();
    // Triangle 1 gets its own copies of its corners, as a uv seam would.
    const Index3 old = m.triangles[1];
    for (int k = 0; k < 3; ++k) {
        m.positions.push_back(m.positions[old[k]]);
        m.triangles[1][k] = static_cast<std::uint32_t>(m.positions.size() - 1);
    }
    EXPECT_EQ(open_edge_count(m, 0, 12), 0u);
}

TEST(MeshEdges, ASingleTriangleIsOpenOnAllSides) {
    const TriangleMesh m = cube();
    EXPECT_EQ(open_edge_count(m, 0, 1), 3u);
}

}  // namespace
}  // namespace sombra
