// glTF meshes drawn several times (spec §23, §24): a mesh several nodes use
// and EXT_mesh_gpu_instancing load as one stored mesh with its instances,
// placed exactly where copies would be; a mesh drawn once stays flattened;
// hostile instancing data is one error line; a scene file multiplies an
// object's instances with the file's, and the statistics count them.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "../../../fuzz/fuzz_harness.h"
#include "io/gltf/gltf.h"
#include "io/gltf/gltf_instancing_test_files.h"
#include "io/gltf/gltf_test_files.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"
#include "io/quicklook.h"
#include "io/scene_json/scene_file.h"
#include "scene/scene.h"
#include "scene/transform.h"

namespace sombra {
namespace {

using gltf_test::add_pyramid;
using gltf_test::GltfFile;
using gltf_test::kInstances;
using namespace gltf_test::instancing;
using testing::TempFolder;

LoadedMesh load(const GltfFile& f, Diagnostics& diag) {
    TempFolder dir;
    const std::filesystem::path path = dir.path / "m.gltf";
    f.save(path);
    return load_gltf(path, diag);
}
LoadedMesh load(const GltfFile& f) {
    Diagnostics diag;
    return load(f, diag);
}

// The corners of every triangle of `m` placed by `t`, in order.
std::vector<Vec3> placed_corners(const TriangleMesh& m, const Transform& t) {
    std::vector<Vec3> out;
    for (const Index3& tri : m.triangles)
        for (std::uint32_t i : tri) out.push_back(transform_point(t, m.positions[i]));
    return out;
}

// The corners of `a` and `b` agree up to float rounding, as sets per
// triangle: a mirrored copy swaps two corners, an instance does not.
void expect_same_triangles(const std::vector<Vec3>& a, const std::vector<Vec3>& b, float tolerance = 1e-5f) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t t = 0; t + 2 < a.size(); t += 3)
        for (std::size_t c = 0; c < 3; ++c) {
            bool found = false;
            for (std::size_t d = 0; d < 3; ++d) found = found || length(a[t + c] - b[t + d]) < tolerance;
            EXPECT_TRUE(found) << "triangle " << t / 3 << " corner " << c;
        }
}

TEST(GltfInstancing, AMeshThreeNodesUseIsStoredOnceWithThreeInstances) {
    const LoadedMesh shared = load(shared_mesh_file()), copied = load(copied_mesh_file());
    EXPECT_TRUE(shared.mesh.triangles.empty());
    ASSERT_EQ(shared.instanced.size(), 1u);
    const InstancedPart& part = shared.instanced[0];
    EXPECT_EQ(part.mesh.triangle_count(), 6u);
    ASSERT_EQ(part.instances.size(), 3u);
    EXPECT_EQ(instance_name(part, 2), "node 2");
    EXPECT_LT(determinant3(part.instances[2]), 0.0f);  // the mirror is the scene builder's to handle
    EXPECT_EQ(fuzz::loaded_mesh_problem(shared), "");  // the fuzz harness's invariants hold
    // Copies stay flattened, each where its instance draws the mesh.
    EXPECT_TRUE(copied.instanced.empty());
    ASSERT_EQ(copied.mesh.triangle_count(), 18u);
    const std::vector<Vec3> flat = placed_corners(copied.mesh, Transform{});
    for (std::size_t k = 0; k < 3; ++k) {
        SCOPED_TRACE(k);
        const std::vector<Vec3> instance = placed_corners(part.mesh, part.instances[k]);
        expect_same_triangles(instance, std::vector<Vec3>(flat.begin() + std::ptrdiff_t(18 * k),
                                                          flat.begin() + std::ptrdiff_t(18 * (k + 1))));
    }
}

TEST(GltfInstancing, AMeshOneNodeDrawsStaysFlattened) {
    GltfFile f = shared_mesh_file();
    add_pyramid(f);
    f.add_node({{"mesh", 1}, {"translation", {0, 3, 0}}});
    f.set_scene({0, 1, 2, 3});
    const LoadedMesh m = load(f);
    EXPECT_EQ(m.mesh.triangle_count(), 6u);
    ASSERT_EQ(m.instanced.size(), 1u);
    EXPECT_EQ(m.instanced[0].instances.size(), 3u);
}

TEST(GltfInstancing, GpuInstancesArePlacedAsNodesWouldPlaceCopies) {
    const LoadedMesh copies = load(gpu_copies_file());
    ASSERT_TRUE(copies.instanced.empty());
    const std::vector<Vec3> flat = placed_corners(copies.mesh, Transform{});
    ASSERT_EQ(flat.size(), 18u * kInstances);
    for (const bool quantized : {false, true}) {
        SCOPED_TRACE(quantized ? "ROTATION as normalised shorts" : "ROTATION as floats");
        const LoadedMesh m = load(gpu_instanced_file(quantized));
        EXPECT_TRUE(m.mesh.triangles.empty());
        ASSERT_EQ(m.instanced.size(), 1u);
        const InstancedPart& part = m.instanced[0];
        ASSERT_EQ(part.instances.size(), std::size_t(kInstances));
        EXPECT_EQ(instance_name(part, 3), "node 0: instance 3");
        for (std::size_t k = 0; k < kInstances; ++k) {
            SCOPED_TRACE(k);
            const std::vector<Vec3> got = placed_corners(part.mesh, part.instances[k]);
            const std::vector<Vec3> want(flat.begin() + std::ptrdiff_t(18 * k),
                                         flat.begin() + std::ptrdiff_t(18 * (k + 1)));
            // A 16-bit quaternion turns corners by up to about 1e-4.
            expect_same_triangles(got, want, quantized ? 1e-3f : 1e-5f);
        }
    }
}

TEST(GltfInstancing, OneGpuInstanceIsDrawnOnceAndStaysFlattened) {
    GltfFile f = gpu_instanced_file();
    for (const char* a : {"TRANSLATION", "ROTATION", "SCALE"}) {
        const int accessor = f.doc["nodes"][0]["extensions"][gltf::kGpuInstancing]["attributes"][a];
        f.doc["accessors"][std::size_t(accessor)]["count"] = 1;
    }
    const LoadedMesh m = load(f);
    EXPECT_TRUE(m.instanced.empty());
    EXPECT_EQ(m.mesh.triangle_count(), 6u);
}

// Hostile instancing data: one line naming the node (or the accessor).
struct HostileCase {
    const char* name;
    std::function<void(GltfFile&)> edit;
    const char* message_part;
};
nlohmann::json& attributes_of(GltfFile& f) {
    return f.doc["nodes"][0]["extensions"][gltf::kGpuInstancing]["attributes"];
}
nlohmann::json& accessor_of(GltfFile& f, const char* attribute) {
    return f.doc["accessors"][attributes_of(f)[attribute].get<std::size_t>()];
}
// Replaces an attribute by one Vec3 array.
void replace_vec3(GltfFile& f, const char* attribute, const std::vector<Vec3>& values) {
    attributes_of(f)[attribute] = f.add_array(values, gltf_test::kFloat, values.size(), "VEC3");
}
std::vector<Vec3> with_one(Vec3 v) {
    std::vector<Vec3> out(kInstances, Vec3{1.0f});
    out[2] = v;
    return out;
}

const HostileCase kHostile[] = {
    {"counts disagree", [](GltfFile& f) { accessor_of(f, "SCALE")["count"] = 4; },
     "node 0: EXT_mesh_gpu_instancing: ROTATION has 5 elements but SCALE has 4"},
    {"a count far beyond the buffer",
     [](GltfFile& f) {
         for (const char* a : {"TRANSLATION", "ROTATION", "SCALE"}) accessor_of(f, a)["count"] = 1000000;
     },
     "overrun bufferView"},
    {"10^8 instances",
     [](GltfFile& f) {
         for (const char* a : {"TRANSLATION", "ROTATION", "SCALE"}) accessor_of(f, a)["count"] = 100000000;
     },
     "100000000 instances would take the file past 8388608"},
    {"more instances than a scene may hold",
     [](GltfFile& f) {
         for (const char* a : {"TRANSLATION", "ROTATION", "SCALE"}) accessor_of(f, a)["count"] = 1 << 24;
     },
     "16777216 instances would take the file past 8388608"},
    {"a NaN translation",
     [](GltfFile& f) {
         replace_vec3(f, "TRANSLATION", with_one(Vec3{0, NAN, 0}));
     },
     "(TRANSLATION of node 0): element 2 is not finite"},
    {"an infinite scale",
     [](GltfFile& f) {
         replace_vec3(f, "SCALE", with_one(Vec3{1, INFINITY, 1}));
     },
     "(SCALE of node 0): element 2 is not finite"},
    {"a zero scale",
     [](GltfFile& f) {
         replace_vec3(f, "SCALE", with_one(Vec3{1, 0, 1}));
     },
     "node 0: EXT_mesh_gpu_instancing: instance 2: SCALE has a zero component"},
    {"a zero rotation",
     [](GltfFile& f) {
         attributes_of(f)["ROTATION"] =
             f.add_array(std::vector<float>(4 * kInstances, 0.0f), gltf_test::kFloat, kInstances, "VEC4");
     },
     "instance 0: ROTATION is not a unit quaternion"},
    {"an unsigned rotation",
     [](GltfFile& f) { accessor_of(f, "ROTATION")["componentType"] = gltf_test::kUnsignedByte; },
     "(ROTATION of node 0): UNSIGNED_BYTE components are not allowed"},
    {"no mesh", [](GltfFile& f) { f.doc["nodes"][0].erase("mesh"); },
     "node 0: EXT_mesh_gpu_instancing: the node has no mesh to instance"},
    {"no data behind the count",
     [](GltfFile& f) {
         for (const char* a : {"TRANSLATION", "ROTATION", "SCALE"}) accessor_of(f, a).erase("bufferView");
     },
     "needs TRANSLATION, ROTATION or SCALE with a bufferView"},
    {"attributes not an object",
     [](GltfFile& f) { f.doc["nodes"][0]["extensions"][gltf::kGpuInstancing]["attributes"] = 3; },
     "'attributes' must be an object"},
};

TEST(GltfInstancing, HostileInstancingIsOneErrorLine) {
    for (const HostileCase& c : kHostile) {
        SCOPED_TRACE(c.name);
        GltfFile f = gpu_instanced_file();
        c.edit(f);
        try {
            load(f);
            ADD_FAILURE() << "loaded";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(c.message_part), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

TEST(GltfInstancing, TheExtensionMayBeRequired) {
    GltfFile f = gpu_instanced_file();
    ASSERT_EQ(f.doc["extensionsRequired"][0], gltf::kGpuInstancing);
    Diagnostics diag;
    EXPECT_EQ(load(f, diag).instanced.size(), 1u);
    EXPECT_TRUE(diag.warnings.empty());
}

// A scene file placing the shared-mesh file (three nodes), next to a
// pyramid one node draws, with an object "transform" and `instances`.
Scene load_scene(const GltfFile& f, const std::string& object_extra, TempFolder& dir,
                 const std::string& transform = R"([{"translate": [0, -1, 0]}])") {
    f.save(dir.path / "m.gltf");
    dir.write("s.json", R"({"camera": {"origin": [0, 0, 9], "look_at": [0, 0, 0]},
        "objects": [{"file": "m.gltf", "transform": )" +
                            transform + object_extra + "}]}");
    Diagnostics diag;
    return load_scene_file(dir.path / "s.json", diag).scene;
}

TEST(GltfInstancing, StatisticsCountStoredAndDrawnTrianglesAndObjectInstancesMultiply) {
    GltfFile f = shared_mesh_file();
    add_pyramid(f);
    f.add_node({{"mesh", 1}, {"translation", {0, 3, 0}}});
    f.set_scene({0, 1, 2, 3});
    TempFolder dir;
    const Scene once = load_scene(f, "", dir);
    EXPECT_EQ(once.geometry.triangle_count(), 6u);  // the pyramid drawn once, flattened
    EXPECT_EQ(once.instanced_meshes.size(), 1u);
    EXPECT_EQ(once.instances.size(), 3u);
    EXPECT_EQ(stored_triangle_count(once), 12u);
    EXPECT_EQ(drawn_triangle_count(once), 24u);

    const Scene twice =
        load_scene(f, R"(, "instances": [[{"translate": [-5, 0, 0]}], [{"translate": [5, 0, 0]}]])", dir);
    EXPECT_EQ(twice.geometry.triangle_count(), 0u);  // with two object instances, everything is instanced
    EXPECT_EQ(twice.instanced_meshes.size(), 2u);
    EXPECT_EQ(twice.instances.size(), 2u + 6u);
    EXPECT_EQ(stored_triangle_count(twice), 12u);
    EXPECT_EQ(drawn_triangle_count(twice), 48u);
    // Node 2 (mirrored, at x = 2.5) in the object's second instance: the
    // file's placement, then the object's transform, then its instance.
    const Instance& last = twice.instances.back();
    expect_same_triangles(
        placed_corners(twice.instanced_meshes[last.mesh], last.object_to_world),
        placed_corners(twice.instanced_meshes[last.mesh],
                       compose(make_scale(Vec3{-1, 1, 1}), make_translate(Vec3{2.5f + 5.0f, -1.0f, 0}))));
    EXPECT_TRUE(last.mirrored);
    EXPECT_EQ(fuzz::scene_problem(LoadedScene{twice, RenderSettings{}}), "");
}

TEST(GltfInstancing, BuilderProblemsNameTheNode) {
    // Each node's scale is invertible on its own; with the object's scale
    // the determinant underflows to 0.
    GltfFile f = shared_mesh_file();
    f.doc["nodes"][1]["scale"] = {1e-13, 1e-13, 1e-13};
    TempFolder dir;
    try {
        load_scene(f, "", dir, R"([{"scale": 1e-13}])");
        ADD_FAILURE() << "loaded";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/objects/0/transform"), std::string::npos) << what;
        EXPECT_NE(what.find("m.gltf: node 1: the node's and the object's transforms together are not invertible"),
                  std::string::npos)
            << what;
    }
    // The quick look has only the file's transforms: a vertex past float's range.
    f = shared_mesh_file();
    f.doc["nodes"][2]["scale"] = {-1e38, 1e38, 1e38};
    f.save(dir.path / "big.gltf");
    Diagnostics diag;
    try {
        make_quicklook_scene(dir.path / "big.gltf", diag);
        ADD_FAILURE() << "loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("big.gltf: node 2: "), std::string::npos) << e.what();
    }
}

TEST(GltfInstancing, QuickLookFramesTheInstances) {
    TempFolder dir;
    shared_mesh_file().save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedScene s = make_quicklook_scene(dir.path / "m.gltf", diag);
    EXPECT_EQ(s.scene.geometry.triangle_count(), 0u);
    EXPECT_EQ(s.scene.instances.size(), 3u);
    EXPECT_EQ(drawn_triangle_count(s.scene), 18u);
    ASSERT_TRUE(s.scene.camera.look_at);
    // The camera looks at the middle of all three (x from −3.5 to 3.5), not of one pyramid's box.
    EXPECT_NEAR(s.scene.camera.look_at->look_at.x, 0.0f, 1e-4f);
    EXPECT_NEAR(s.scene.camera.look_at->look_at.y, 0.75f, 1e-4f);
    EXPECT_GT(length(s.scene.camera.look_at->origin - s.scene.camera.look_at->look_at), 8.0f);
}

}  // namespace
}  // namespace sombra
