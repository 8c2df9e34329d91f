// The scene's builder: meshes placed in world space, tables joined and
// renumbered, objects recorded, problems reported rather than thrown.
#include "scene/scene_builder.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <utility>

namespace sombra {
namespace {

// One triangle (0,0,0), (1,0,0), (0,1,0) with a normal and a uv at every
// corner, its triangle naming material `material` of its own list.
TriangleMesh corner_triangle(std::uint32_t material = 0) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}};
    m.normals = {{0, 0, 2}};  // not unit: a placed normal is renormalised
    m.normal_indices = {{0, 0, 0}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}};
    m.uv_indices = {{0, 1, 2}};
    m.material_ids = {material};
    return m;
}

Texture texture_named(const std::string& source) {
    Texture t;
    t.source = source;
    t.width = t.height = 1;
    t.channels = 1;
    t.texels = {0.5f};
    return t;
}

Material material_with_kd_texture(const std::string& name, std::uint32_t texture) {
    Material m;
    m.name = name;
    m.textures.kd.texture = texture;
    return m;
}

TEST(SceneBuilder, PlacedMeshesMoveMirrorAndRenormalise) {
    SceneBuilder b;
    const std::uint32_t grey = b.add_material(Material{"grey", MaterialType::Diffuse, Vec3{0.5f}});
    ASSERT_EQ(b.add_mesh(corner_triangle(), {}, {},
                         MeshPlacement{"/objects/0", "a.obj", make_translate({0, 0, 5}), grey}),
              MeshProblem::None);
    // A mirror (x → −x) keeps the winding's side by swapping corners 1 and 2.
    ASSERT_EQ(b.add_mesh(corner_triangle(), {}, {}, MeshPlacement{"/objects/1", "a.obj", make_scale({-1, 1, 1}), grey}),
              MeshProblem::None);
    const Scene s = b.finish();
    ASSERT_EQ(s.geometry.triangle_count(), 2u);
    EXPECT_EQ(s.geometry.positions[2], Vec3(0, 1, 5));
    EXPECT_EQ(s.geometry.triangles[1], (Index3{3, 5, 4}));
    EXPECT_EQ(s.geometry.uv_indices[1], (Index3{3, 5, 4}));
    EXPECT_EQ(s.geometry.normals[0], Vec3(0, 0, 1));
    EXPECT_EQ(s.geometry.material_ids, (std::vector<std::uint32_t>{grey, grey}));
    ASSERT_EQ(s.objects.size(), 2u);
    EXPECT_EQ(s.objects[1].name, "/objects/1");
    EXPECT_EQ(s.objects[1].file, "a.obj");
    EXPECT_EQ(s.objects[1].first_triangle, 1u);
    EXPECT_EQ(s.objects[1].triangle_count, 1u);
    // finish() derives the bits shading reads.
    ASSERT_EQ(s.geometry.complete_normals.size(), 1u);
    EXPECT_EQ(s.geometry.complete_normals[0], 3u);
    EXPECT_EQ(s.geometry.complete_uvs[0], 3u);
}

TEST(SceneBuilder, UnplacedMeshesJoinBitForBit) {
    TriangleMesh m = corner_triangle();
    m.positions[0] = Vec3{-0.0f, 0, 0};  // a transform, even the identity, would make it +0
    SceneBuilder b;
    ASSERT_EQ(b.add_mesh(m, {}, {}, MeshPlacement{"m", "m.obj", std::nullopt, std::nullopt}), MeshProblem::None);
    ASSERT_EQ(b.add_mesh(m, {}, {}, MeshPlacement{"m", "m.obj", std::nullopt, std::nullopt}), MeshProblem::None);
    const Scene s = b.finish();
    EXPECT_TRUE(std::signbit(s.geometry.positions[3].x));
    EXPECT_EQ(s.geometry.normals[1], Vec3(0, 0, 2));  // copied, not renormalised
    EXPECT_EQ(s.geometry.triangles[1], (Index3{3, 4, 5}));
}

TEST(SceneBuilder, MeshTablesJoinTheScenesSharedBySource) {
    SceneBuilder b;
    const std::uint32_t wood = b.add_texture(texture_named("wood.png"));
    b.add_material(material_with_kd_texture("scene's", wood));
    // The mesh's own table: "metal.png" is new, "wood.png" is the scene's.
    const std::vector<Texture> textures{texture_named("metal.png"), texture_named("wood.png")};
    const std::vector<Material> materials{material_with_kd_texture("metal", 0), material_with_kd_texture("wood", 1)};
    TriangleMesh mesh = corner_triangle(1);
    mesh.positions.push_back({1, 1, 0});
    mesh.triangles.push_back({1, 3, 2});
    mesh.material_ids.push_back(7);  // names no material: the default one
    mesh.normal_indices.push_back({0, 0, 0});
    mesh.uv_indices.push_back({1, 2, 2});
    ASSERT_EQ(b.add_mesh(mesh, materials, textures, MeshPlacement{"o", "m.obj", Transform{}, std::nullopt}),
              MeshProblem::None);
    const Scene s = b.finish();
    ASSERT_EQ(s.textures.size(), 2u);
    ASSERT_EQ(s.materials.size(), 4u);  // the scene's, metal, wood, the default
    EXPECT_EQ(s.materials[1].textures.kd.texture, 1u);
    EXPECT_EQ(s.materials[2].textures.kd.texture, wood);
    EXPECT_TRUE(s.materials[1].textured);
    EXPECT_EQ(s.materials[3].name, "default");
    EXPECT_EQ(s.geometry.material_ids, (std::vector<std::uint32_t>{2, 3}));
}

TEST(SceneBuilder, MovedMeshEqualsCopiedMesh) {
    const std::vector<Material> materials{material_with_kd_texture("m", 0)};
    const std::vector<Texture> textures{texture_named("t.png")};
    const MeshPlacement placement{"model.glb", "dir/model.glb", std::nullopt, std::nullopt};
    SceneBuilder copied, moved;
    ASSERT_EQ(copied.add_mesh(corner_triangle(), materials, textures, placement), MeshProblem::None);
    std::vector<Material> m = materials;
    std::vector<Texture> t = textures;
    ASSERT_EQ(moved.add_mesh(corner_triangle(), std::move(m), std::move(t), placement), MeshProblem::None);
    const Scene a = copied.finish(), b = moved.finish();
    EXPECT_EQ(a.geometry.positions, b.geometry.positions);
    EXPECT_EQ(a.geometry.triangles, b.geometry.triangles);
    EXPECT_EQ(a.geometry.normal_indices, b.geometry.normal_indices);
    EXPECT_EQ(a.geometry.uv_indices, b.geometry.uv_indices);
    EXPECT_EQ(a.geometry.material_ids, b.geometry.material_ids);
    EXPECT_EQ(a.geometry.complete_uvs, b.geometry.complete_uvs);
    ASSERT_EQ(b.materials.size(), 1u);
    EXPECT_EQ(b.materials[0].textures.kd.texture, 0u);
    EXPECT_TRUE(b.materials[0].textured);
    ASSERT_EQ(b.objects.size(), 1u);
    EXPECT_EQ(b.objects[0].triangle_count, 1u);
}

TEST(SceneBuilder, ProblemsAreReportedInOrder) {
    TriangleMesh bad = corner_triangle();
    bad.triangles.push_back({0, 1, 3});  // vertex 3 does not exist
    bad.positions[1] = {4, 0, 0};        // 4 × 3e38 overflows a float
    SceneBuilder b;
    EXPECT_EQ(b.add_mesh(bad, {}, {}, MeshPlacement{"o", "", Transform{}, 0}), MeshProblem::BadVertexIndex);
    // Placement is checked first: a finite vertex sent to infinity.
    EXPECT_EQ(b.add_mesh(bad, {}, {}, MeshPlacement{"o", "", make_scale({3e38f, 1, 1}), 0}),
              MeshProblem::NonFinitePlacement);
    SceneBuilder empty;
    EXPECT_EQ(empty.add_mesh(std::move(bad), {}, {}, MeshPlacement{"o", "", std::nullopt, std::nullopt}),
              MeshProblem::BadVertexIndex);
}

TEST(SceneBuilder, CameraLightsAndBackgroundAreKeptInOrder) {
    SceneBuilder b;
    CameraSpec camera;
    camera.look_at = CameraLookAt{{0, 0, 5}, {0, 0, 0}};
    b.set_camera(camera);
    b.set_background(Vec3{0.25f});
    b.add_light(make_point_light({0, 1, 0}, Vec3{1.0f}));
    b.add_light(make_directional_light({0, -1, 0}, Vec3{2.0f}));
    const Scene s = b.finish();
    ASSERT_TRUE(s.camera.look_at);
    EXPECT_EQ(s.camera.look_at->origin, Vec3(0, 0, 5));
    EXPECT_EQ(s.background, Vec3(0.25f));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[1].type, LightType::Directional);
    EXPECT_EQ(b.scene().lights.size(), 0u);  // finish() leaves the builder empty
}

TEST(MeshSizes, SumOverMeshes) {
    MeshSizes sum = sizes_of(corner_triangle());
    TriangleMesh bare;
    bare.positions = {{0, 0, 0}};
    sum += sizes_of(bare);
    EXPECT_EQ(sum.positions, 4u);
    EXPECT_EQ(sum.triangles, 1u);
    EXPECT_EQ(sum.normals, 1u);
    EXPECT_TRUE(sum.any_uvs);
    EXPECT_FALSE(sum.any_colors);
}

}  // namespace
}  // namespace sombra
