// Texture coordinates through the loaders and the scene: OBJ `vt` and PLY
// u v / s t / texture_u texture_v kept as written, one uv index per triangle
// corner (kNoUv where a face has none), through polygon splitting and the
// concatenation of objects into Scene::geometry.
#include <gtest/gtest.h>

#include "io/mesh_file.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"

namespace sombra {
namespace {

using testing::TempFolder;

constexpr Index3 kNoUvs{kNoUv, kNoUv, kNoUv};

// The uv of each corner of triangle t, or (-1, -1) for kNoUv.
std::array<Vec2, 3> corner_uvs(const TriangleMesh& mesh, std::size_t t) {
    std::array<Vec2, 3> out;
    for (int c = 0; c < 3; ++c) {
        const std::uint32_t i = mesh.uv_indices[t][c];
        out[c] = i == kNoUv ? Vec2{-1, -1} : mesh.uvs[i];
    }
    return out;
}

// A quad with texture coordinates (split as a fan into two triangles), then a
// triangle without, then one whose corners name texture coordinates negatively.
constexpr const char* kQuadObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1 0.5\nvt 0 1\n"
    "f 1/1 2/2 3/3 4/4\n"
    "f 1 2 3\n"
    "f 1/-4/ 3/-2 4/-1\n";

TEST(Uvs, ObjTextureCoordinatesFollowTheFanSplit) {
    TempFolder tmp;
    Diagnostics diag;
    const TriangleMesh mesh = load_obj(tmp.write("quad.obj", kQuadObj), diag).mesh;
    ASSERT_EQ(mesh.triangle_count(), 4u);
    ASSERT_TRUE(mesh.has_uvs());
    ASSERT_EQ(mesh.uv_indices.size(), mesh.triangles.size());
    EXPECT_EQ(mesh.uvs.size(), 4u);
    // Fan from corner 0: (0, 1, 2), (0, 2, 3); v = 0 is stored as read (no flip).
    EXPECT_EQ(corner_uvs(mesh, 0), (std::array<Vec2, 3>{Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}}));
    EXPECT_EQ(corner_uvs(mesh, 1), (std::array<Vec2, 3>{Vec2{0, 0}, Vec2{1, 1}, Vec2{0, 1}}));
    EXPECT_EQ(mesh.uv_indices[2], kNoUvs);
    EXPECT_EQ(corner_uvs(mesh, 3), (std::array<Vec2, 3>{Vec2{0, 0}, Vec2{1, 1}, Vec2{0, 1}}));
}

TEST(Uvs, ObjWithoutTextureCoordinatesHasNone) {
    TempFolder tmp;
    Diagnostics diag;
    const TriangleMesh mesh =
        load_obj(tmp.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nf 1 2 3\n"), diag).mesh;
    EXPECT_FALSE(mesh.has_uvs());
    EXPECT_TRUE(mesh.uvs.empty());
}

TEST(Uvs, PlyVertexTextureCoordinatesUnderEachName) {
    for (const auto& [u, v] : {std::pair{"u", "v"}, std::pair{"s", "t"}, std::pair{"texture_u", "texture_v"}}) {
        SCOPED_TRACE(u);
        TempFolder tmp;
        Diagnostics diag;
        const std::string ply = std::string(
                                    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                    "property float z\nproperty float ") +
                                u + "\nproperty float " + v +
                                "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                "0 0 0 0 0\n1 0 0 0.25 0\n1 1 0 0.25 0.75\n0 1 0 0 0.75\n4 0 1 2 3\n";
        const TriangleMesh mesh = load_ply(tmp.write("quad.ply", ply), diag).mesh;
        ASSERT_EQ(mesh.triangle_count(), 2u);
        ASSERT_TRUE(mesh.has_uvs());
        EXPECT_EQ(corner_uvs(mesh, 0), (std::array<Vec2, 3>{Vec2{0, 0}, Vec2{0.25f, 0}, Vec2{0.25f, 0.75f}}));
        EXPECT_EQ(corner_uvs(mesh, 1), (std::array<Vec2, 3>{Vec2{0, 0}, Vec2{0.25f, 0.75f}, Vec2{0, 0.75f}}));
    }
}

TEST(Uvs, SceneAssemblyOffsetsUvIndicesAndMarksObjectsWithout) {
    TempFolder tmp;
    tmp.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    tmp.write("quad.obj", kQuadObj);
    const auto scene_path =
        tmp.write("scene.json", R"({"camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]}, "objects": [
            {"file": "tri.obj"},
            {"file": "quad.obj"},
            {"file": "quad.obj", "transform": [{"translate": [3, 0, 0]}]}]})");
    Diagnostics diag;
    const TriangleMesh world = load_scene_file(scene_path, diag).scene.geometry;
    ASSERT_EQ(world.triangle_count(), 1u + 4u + 4u);
    ASSERT_EQ(world.uv_indices.size(), world.triangles.size());
    EXPECT_EQ(world.uvs.size(), 8u);         // each object's own copy
    EXPECT_EQ(world.uv_indices[0], kNoUvs);  // tri.obj has none
    EXPECT_EQ(world.uv_indices[1], (Index3{0, 1, 2}));
    EXPECT_EQ(world.uv_indices[5], (Index3{4, 5, 6}));  // the second quad: offset by the first's 4
    EXPECT_EQ(world.uv_indices[7], kNoUvs);
    for (std::size_t t = 1; t < 5; ++t) {
        EXPECT_EQ(corner_uvs(world, t), corner_uvs(world, t + 4)) << "transforms leave uvs unchanged";
    }
}

}  // namespace
}  // namespace sombra
