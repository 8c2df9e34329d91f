// The outline of a mesh: boundaries, creases and silhouettes, and nothing of
// a flat or smooth interior.
#include "explain/outline.h"

#include <gtest/gtest.h>

#include "render/test_meshes.h"

namespace sombra {
namespace {

// A unit cube of 8 shared corners and 12 triangles, wound outwards.
TriangleMesh cube() {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(
            {static_cast<float>(i & 1), static_cast<float>((i >> 1) & 1), static_cast<float>((i >> 2) & 1)});
    auto quad = [&m](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
        m.material_ids.insert(m.material_ids.end(), {0, 0});
    };
    quad(0, 2, 3, 1);  // z = 0
    quad(4, 5, 7, 6);  // z = 1
    quad(0, 1, 5, 4);  // y = 0
    quad(2, 6, 7, 3);  // y = 1
    quad(0, 4, 6, 2);  // x = 0
    quad(1, 3, 7, 5);  // x = 1
    return m;
}

TEST(Outline, CubeGivesItsTwelveEdgesAndNoDiagonal) {
    const std::vector<Segment> lines = outline_segments(cube(), normalize(Vec3{0.3f, -0.5f, 0.8f}), 1000);
    EXPECT_EQ(lines.size(), 12u);
    for (const Segment& s : lines) EXPECT_FLOAT_EQ(length(s.b - s.a), 1.0f);  // diagonals are √2
}

TEST(Outline, OpenTriangleIsAllBoundary) {
    TriangleMesh m;
    testing::add_triangle(m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    EXPECT_EQ(outline_segments(m, {0, 0, -1}, 1000).size(), 3u);
}

TEST(Outline, FlatQuadShowsOnlyItsBorder) {
    TriangleMesh m;
    testing::add_quad(m, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);
    EXPECT_EQ(outline_segments(m, {0, 0, -1}, 1000).size(), 4u);
}

TEST(Outline, SilhouetteOfAGentleFoldSeenEdgeOn) {
    // Two faces meeting at 10° (not a crease): an outline only when the view
    // sees one from the front and the other from behind.
    TriangleMesh m;
    const float z = std::tan(10.0f * 3.14159265f / 180.0f);
    m.positions = {{0, 0, 0}, {0, 1, 0}, {1, 0, z}, {-1, 0, z}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}};
    m.material_ids = {0, 0};
    // Face-on: only the four boundary edges.
    EXPECT_EQ(outline_segments(m, {0, 0, 1}, 1000).size(), 4u);
    // Along the x axis one face turns towards the viewer and the other away: the fold shows.
    EXPECT_EQ(outline_segments(m, {1, 0, 0}, 1000).size(), 5u);
}

TEST(Outline, BudgetKeepsTheLongest) {
    TriangleMesh m;
    testing::add_triangle(m, {0, 0, 0}, {4, 0, 0}, {0, 1, 0}, 0);
    const std::vector<Segment> lines = outline_segments(m, {0, 0, 1}, 1);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NEAR(length(lines[0].b - lines[0].a), std::sqrt(17.0f), 1e-5f);  // the hypotenuse
}

TEST(Outline, HugeMeshesGetTheirBoundingBox) {
    const std::vector<Segment> lines = outline_segments(cube(), {0, 0, 1}, 1000, 4);
    EXPECT_EQ(lines.size(), 12u);
    for (const Segment& s : lines) EXPECT_FLOAT_EQ(length(s.b - s.a), 1.0f);
}

}  // namespace
}  // namespace sombra
