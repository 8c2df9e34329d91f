#include "scene/corner_attributes.h"

#include <gtest/gtest.h>

namespace sombra {
namespace {

// 130 triangles (three 64-bit words) with normals at all three corners of
// every third one, at two corners of the next, none at the third; uvs at all
// three corners of triangles 0 … 69 only.
TriangleMesh mixed_mesh() {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.normals = {{0, 0, 1}};
    mesh.uvs = {{0, 0}};
    for (std::uint32_t t = 0; t < 130; ++t) {
        mesh.triangles.push_back({0, 1, 2});
        mesh.normal_indices.push_back(t % 3 == 0   ? Index3{0, 0, 0}
                                      : t % 3 == 1 ? Index3{0, kNoNormal, 0}
                                                   : Index3{kNoNormal, kNoNormal, kNoNormal});
        mesh.uv_indices.push_back(t < 70 ? Index3{0, 0, 0} : Index3{kNoUv, kNoUv, kNoUv});
    }
    return mesh;
}

TEST(CompleteCorners, ABitPerTriangleWithAllThreeCorners) {
    TriangleMesh mesh = mixed_mesh();
    mark_complete_corners(mesh);
    ASSERT_EQ(mesh.complete_normals.size(), 3u);
    ASSERT_EQ(mesh.complete_uvs.size(), 3u);
    for (std::uint32_t t = 0; t < 130; ++t) {
        EXPECT_EQ((mesh.complete_normals[t / 64] >> (t % 64) & 1u) != 0, t % 3 == 0) << t;
        EXPECT_EQ((mesh.complete_uvs[t / 64] >> (t % 64) & 1u) != 0, t < 70) << t;
        EXPECT_EQ(may_be_complete(mesh.complete_normals, t), t % 3 == 0) << t;
        EXPECT_EQ(may_be_complete(mesh.complete_uvs, t), t < 70) << t;
    }
    EXPECT_EQ(mesh.complete_normals[2] >> 2, 0u);  // no bit beyond the last triangle
}

TEST(CompleteCorners, EmptyWithoutTheAttributeAndNotDerivedMeansReadTheIndices) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}};
    mark_complete_corners(mesh);
    EXPECT_TRUE(mesh.complete_normals.empty());
    EXPECT_TRUE(mesh.complete_uvs.empty());
    EXPECT_TRUE(may_be_complete(mesh.complete_normals, 0));

    // Derived again after the attribute appears: stale bits are replaced.
    mesh.normals = {{0, 0, 1}};
    mesh.normal_indices = {{0, 0, 0}};
    mark_complete_corners(mesh);
    EXPECT_EQ(mesh.complete_normals, std::vector<std::uint64_t>{1u});
}

}  // namespace
}  // namespace sombra
