// Meshes from arrays (io/array_mesh.h) and the objects that name them in
// scene text: the same mesh as the OBJ reader makes of the same numbers, and
// "mesh" an unknown key in any scene file.
#include "io/array_mesh.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/scene_json/scene_file.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;

TEST(ArrayMesh, IsTheMeshTheObjReaderMakesOfTheSameNumbers) {
    const fs::path obj = fs::temp_directory_path() / ("sombra_array_mesh_" + std::to_string(::getpid()) + ".obj");
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 2\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1/1 2/2/2 3/3/3\nf 1/1/1 3/3/3 4/4/4\n";
    Diagnostics diag;
    const LoadedMesh from_file = load_mesh_file(obj, diag);
    fs::remove(obj);
    const std::vector<std::uint32_t> corners{0, 1, 2, 0, 2, 3};
    const LoadedMesh from_arrays =
        make_array_mesh("arrays", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, corners,
                        {{0, 0, 2}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, diag);
    const TriangleMesh& a = from_arrays.mesh;
    const TriangleMesh& b = from_file.mesh;
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.normal_indices, b.normal_indices);
    EXPECT_EQ(a.uv_indices, b.uv_indices);
    EXPECT_EQ(a.material_ids, b.material_ids);
    ASSERT_EQ(a.normals.size(), b.normals.size());
    for (std::size_t i = 0; i < a.normals.size(); ++i) {
        EXPECT_EQ(a.normals[i].x, b.normals[i].x);
        EXPECT_EQ(a.normals[i].z, b.normals[i].z);  // the first one normalised, as the reader does
    }
    ASSERT_EQ(from_arrays.materials.size(), 1u);
    EXPECT_EQ(from_arrays.materials[0].name, from_file.materials[0].name);
}

TEST(ArrayMesh, RefusesWhatWouldReadPastTheArrays) {
    Diagnostics diag;
    const std::vector<Vec3> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<std::uint32_t> past{0, 1, 3};
    EXPECT_THROW(make_array_mesh("m", tri, past, {}, {}, diag), Error);
    const std::vector<std::uint32_t> ok{0, 1, 2};
    EXPECT_THROW(make_array_mesh("m", tri, ok, {{0, 0, 1}}, {}, diag), Error);
    EXPECT_THROW(make_array_mesh("m", {{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}}, ok, {}, {}, diag), Error);
    EXPECT_EQ(make_array_mesh("m", tri, ok, {}, {}, diag).mesh.triangle_count(), 1u);
}

TEST(ArrayMesh, ObjectsNameGivenMeshesOnlyWhenThereAreSome) {
    const std::string text = R"({"camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]},
                                 "objects": [{"mesh": 0, "transform": [{"scale": 2}]}]})";
    Diagnostics diag;
    try {
        load_scene_text(text, "scene.json", diag);
        FAIL() << "a scene file took \"mesh\"";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "scene.json: /objects/0/mesh: unknown key 'mesh'");
    }
    const LoadedMesh mesh =
        make_array_mesh("m", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, std::vector<std::uint32_t>{0, 1, 2}, {}, {}, diag);
    const LoadedMesh* given[] = {&mesh};
    const LoadedScene loaded = load_scene_text(text, "scene.json", diag, given);
    ASSERT_EQ(loaded.scene.geometry.triangle_count(), 1u);
    EXPECT_EQ(loaded.scene.geometry.positions[1].x, 2.0f);
    const std::string past = R"({"camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]}, "objects": [{"mesh": 1}]})";
    EXPECT_THROW(load_scene_text(past, "scene.json", diag, given), Error);
}

}  // namespace
}  // namespace sombra
