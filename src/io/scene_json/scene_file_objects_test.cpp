// Objects of scene files (spec §2, §8, §11): transforms in listed order, normals
// by the inverse transpose, meshes joined with their materials, paths from
// the scene's folder, and winding kept under mirroring transforms.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;
using testing::winding_normal;

class SceneObjects : public testing::SceneFileTest {};

TEST_F(SceneObjects, TransformsApplyInListedOrder) {
    const auto vertex = [&](const std::string& transform) {
        const Scene s = load(with_objects(R"({"file": "tri.obj", "transform": )" + transform + "}"));
        return s.geometry.positions.at(s.geometry.triangles.at(0)[0]);  // file vertex (1, 0, 0)
    };
    EXPECT_EQ(vertex(R"([{"scale": 2}, {"translate": [1, 0, 0]}])"), Vec3(3, 0, 0));
    EXPECT_EQ(vertex(R"([{"translate": [1, 0, 0]}, {"scale": 2}])"), Vec3(4, 0, 0));
    EXPECT_EQ(vertex(R"([{"scale": [3, 1, 1]}])"), Vec3(3, 0, 0));
    EXPECT_EQ(vertex(R"([{"rotate": {"axis": [0, 1, 0], "degrees": 90}}])"), Vec3(0, 0, -1));
    EXPECT_EQ(vertex(R"([{"matrix": [1,0,0,5, 0,1,0,6, 0,0,1,7, 0,0,0,1]}])"), Vec3(6, 6, 7));
    EXPECT_EQ(vertex(R"([{"matrix": [0,-1,0,0, 1,0,0,0, 0,0,1,0, 0,0,0,1]}])"), Vec3(0, 1, 0));
    EXPECT_EQ(vertex("[]"), Vec3(1, 0, 0));
}

TEST_F(SceneObjects, NormalsFollowTheInverseTranspose) {
    const Scene s = load(with_objects(R"({"file": "tilted.obj", "transform": [{"scale": [1, 4, 1]}]})"));
    const TriangleMesh& g = s.geometry;
    ASSERT_TRUE(g.has_normals());
    ASSERT_EQ(g.normal_indices.size(), 1u);
    const Index3 t = g.triangles[0];
    const Vec3 e1 = g.positions[t[1]] - g.positions[t[0]], e2 = g.positions[t[2]] - g.positions[t[0]];
    for (int c = 0; c < 3; ++c) {
        ASSERT_NE(g.normal_indices[0][c], kNoNormal);
        const Vec3 n = g.normals.at(g.normal_indices[0][c]);
        EXPECT_NEAR(length(n), 1.0f, 1e-6f);
        EXPECT_NEAR(dot(n, normalize(e1)), 0.0f, 1e-6f);
        EXPECT_NEAR(dot(n, normalize(e2)), 0.0f, 1e-6f);
        EXPECT_GT(n.x, 0.0f);  // still on the side the file's normal was
    }
}

TEST_F(SceneObjects, ObjectsConcatenateWithOffsetsAndMaterials) {
    const std::string materials = R"({"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}})";
    const Scene s = load(with_objects(
        R"({"file": "two.obj", "material": "grey"}, {"file": "tilted.obj", "transform": [{"translate": [0, 0, 10]}]}, {"file": "two.obj"})",
        materials));
    const TriangleMesh& g = s.geometry;
    ASSERT_EQ(g.triangle_count(), 5u);
    ASSERT_EQ(g.positions.size(), 4u + 3u + 4u);
    // Indices point at the right object's vertices.
    EXPECT_EQ(g.positions[g.triangles[2][0]], Vec3(1, 0, 10));
    EXPECT_EQ(g.triangles[3], (Index3{7, 8, 9}));
    EXPECT_EQ(g.triangles[4], (Index3{8, 10, 9}));
    // Only the middle object has normals; the others are marked as having none.
    ASSERT_EQ(g.normal_indices.size(), 5u);
    EXPECT_EQ(g.normal_indices[0], (Index3{kNoNormal, kNoNormal, kNoNormal}));
    EXPECT_NE(g.normal_indices[2][0], kNoNormal);
    EXPECT_EQ(g.normal_indices[4], (Index3{kNoNormal, kNoNormal, kNoNormal}));
    // Loading derives which triangles have all three (TriangleMesh::complete_normals).
    EXPECT_EQ(g.complete_normals, std::vector<std::uint64_t>{0b00100u});
    EXPECT_TRUE(g.complete_uvs.empty());
    // The override gives both triangles "grey"; without it, the file's own materials.
    ASSERT_EQ(g.material_ids.size(), 5u);
    EXPECT_EQ(s.materials.at(g.material_ids[0]).name, "grey");
    EXPECT_EQ(s.materials.at(g.material_ids[1]).name, "grey");
    const Material& red = s.materials.at(g.material_ids[3]);
    const Material& shiny = s.materials.at(g.material_ids[4]);
    EXPECT_EQ(red.name, "red");
    EXPECT_EQ(red.kd, Vec3(1, 0, 0));
    EXPECT_EQ(shiny.type, MaterialType::Phong);
    EXPECT_EQ(shiny.ks, Vec3(0.5f));
}

TEST_F(SceneObjects, RelativeMeshPathsFollowTheSceneFolder) {
    const fs::path sub = dir / "models" / "nested.json";
    std::ofstream(sub) << with_objects(R"({"file": "../tri.obj"})");
    const Scene s = load_scene_file(sub, diag).scene;
    EXPECT_EQ(s.geometry.triangle_count(), 1u);
}

// Spec §11: the outside of glass is the winding normal's side, negated under
// a mirroring transform; sombra swaps two corners so the world winding keeps
// pointing to the same side of the surface.
TEST_F(SceneObjects, MirroringTransformKeepsTheWindingSide) {
    const Scene plain = load(scene(""));
    EXPECT_EQ(plain.geometry.triangles[0], (Index3{0, 1, 2}));
    const Vec3 n = winding_normal(plain.geometry, 0);  // (1, 1, 1): away from the origin

    const Scene mirrored = load(scene("", R"([{"file": "tri.obj", "transform": [{"scale": [-1, 1, 1]}]}])"));
    EXPECT_EQ(mirrored.geometry.triangles[0], (Index3{0, 2, 1}));
    const Vec3 m = winding_normal(mirrored.geometry, 0);
    EXPECT_EQ(m, (Vec3{-n.x, n.y, n.z}));  // the mirror image of n: still away from the origin

    // Two mirrors make a rotation: no swap.
    const Scene twice = load(scene("", R"([{"file": "tri.obj", "transform": [{"scale": [-1, -1, 1]}]}])"));
    EXPECT_EQ(twice.geometry.triangles[0], (Index3{0, 1, 2}));
}

TEST_F(SceneObjects, MirroringTransformSwapsNormalAndUvCornersAlong) {
    const Scene s = load(scene("", R"([{"file": "normals.obj", "transform": [{"scale": [-2, 1, 1]}]}])"));
    const TriangleMesh& g = s.geometry;
    ASSERT_EQ(g.triangle_count(), 1u);
    const Vec2 uv_of_vertex[3] = {{0, 0}, {1, 0}, {0, 1}};
    for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = g.triangles[0][c];
        // Each corner's normal still points along its own (mirrored) position.
        EXPECT_EQ(g.normals[g.normal_indices[0][c]], normalize(g.positions[v])) << c;
        EXPECT_EQ(g.uvs[g.uv_indices[0][c]], uv_of_vertex[v]) << c;
    }
}

}  // namespace
}  // namespace sombra
