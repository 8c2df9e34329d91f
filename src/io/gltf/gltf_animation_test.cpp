// glTF animations (spec §22): translation, rotation and scale channels
// with LINEAR, STEP and CUBICSPLINE samplers move their nodes' instances
// on the scene's clock, children with their parents, against transforms
// computed by hand; a scene file's object transform follows the node's;
// hostile animation data is one error line; unanimated files are unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
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
#include "scene/animation.h"
#include "scene/scene.h"

namespace sombra {
namespace {

using gltf_test::add_pyramid;
using gltf_test::GltfFile;
using gltf_test::kFloat;
using gltf_test::kShort;
using testing::TempFolder;

// Adds a sampler to animation 0; returns its index.
int add_sampler(GltfFile& f, const std::vector<float>& times, const std::vector<float>& values, const char* type,
                const char* interpolation) {
    const std::size_t width = std::string(type) == "VEC4" ? 4 : 3;
    const int in = f.add_array(times, kFloat, times.size(), "SCALAR");
    const int out = f.add_array(values, kFloat, values.size() / width, type);
    f.doc["animations"][0]["samplers"].push_back({{"input", in}, {"output", out}, {"interpolation", interpolation}});
    return int(f.doc["animations"][0]["samplers"].size()) - 1;
}
void add_channel(GltfFile& f, int sampler, int node, const char* path) {
    f.doc["animations"][0]["channels"].push_back({{"sampler", sampler}, {"target", {{"node", node}, {"path", path}}}});
}

const float kS45 = std::sin(0.25f * 3.14159265f), kC45 = std::cos(0.25f * 3.14159265f);

// Node 0 (pyramid mesh 0): translation LINEAR (0,0,0) → (4,0,0) and
// rotation LINEAR 0° → 90° about y over 0..2 s, scale STEP 1 then 2 at 1 s.
// Node 1, its child, draws mesh 0 at (0, 3, 0). Node 2 (mesh 1, drawn
// once) has a CUBICSPLINE translation over 0..2 s. Node 3 (mesh 2) is static.
GltfFile animated_file() {
    GltfFile f;
    add_pyramid(f);
    add_pyramid(f);
    add_pyramid(f);
    f.add_node({{"mesh", 0}, {"children", {1}}});
    f.add_node({{"mesh", 0}, {"translation", {0, 3, 0}}});
    f.add_node({{"mesh", 1}, {"translation", {9, 9, 9}}});  // the rest pose, replaced by the animation
    f.add_node({{"mesh", 2}, {"translation", {0, 0, -7}}});
    f.set_scene({0, 2, 3});
    add_channel(f, add_sampler(f, {0, 2}, {0, 0, 0, 4, 0, 0}, "VEC3", "LINEAR"), 0, "translation");
    add_channel(f, add_sampler(f, {0, 2}, {0, 0, 0, 1, 0, kS45, 0, kC45}, "VEC4", "LINEAR"), 0, "rotation");
    add_channel(f, add_sampler(f, {0, 1}, {1, 1, 1, 2, 2, 2}, "VEC3", "STEP"), 0, "scale");
    // In-tangent, value, out-tangent per key: v0 = (0,5,0), b0 = (2,0,0); a1 = (1,0,0), v1 = (1,5,0).
    add_channel(f,
                add_sampler(f, {0, 2}, {0, 0, 0, 0, 5, 0, 2, 0, 0, 1, 0, 0, 1, 5, 0, 0, 0, 0}, "VEC3", "CUBICSPLINE"),
                2, "translation");
    return f;
}

void expect_near(const Transform& got, const Transform& want, float tolerance = 1e-5f) {
    for (int k = 0; k < 16; ++k) EXPECT_NEAR(got.m[k], want.m[k], tolerance) << "element " << k;
}

// Node 0's transform by hand: T · R_y · S.
Transform node0(float x, float degrees, float scale) {
    return compose(compose(make_scale(Vec3{scale}), make_rotate(Vec3{0, 1, 0}, degrees)),
                   make_translate(Vec3{x, 0, 0}));
}

LoadedScene quick_look(const GltfFile& f, TempFolder& dir, Diagnostics& diag) {
    f.save(dir.path / "m.gltf");
    return make_quicklook_scene(dir.path / "m.gltf", diag);
}

TEST(GltfAnimation, ChannelsMoveTheirNodesAndChildren) {
    TempFolder dir;
    Diagnostics diag;
    LoadedScene s = quick_look(animated_file(), dir, diag);
    EXPECT_TRUE(diag.warnings.empty());
    Scene& scene = s.scene;
    // The static pyramid stays flattened; the animated ones are instances, the one drawn once too.
    EXPECT_EQ(scene.geometry.triangle_count(), 6u);
    ASSERT_EQ(scene.instances.size(), 3u);
    ASSERT_TRUE(scene.animation);
    EXPECT_EQ(scene.animation->fps, 24.0);
    EXPECT_EQ(scene.animation->first_frame, 0);
    EXPECT_EQ(scene.animation->last_frame, 48);  // 2 s × 24
    const Transform child = make_translate(Vec3{0, 3, 0});
    struct Moment {
        double time;
        Transform node0, node2;
    };
    // Cubic at 1 s (s = 0.5, interval 2): 0.5·v0 + 0.125·2·b0 + 0.5·v1 − 0.125·2·a1 → x = 0.75;
    // at 0.5 s (s = 0.25): 0.140625·2·2 + 0.15625·1 − 0.046875·2·1 → x = 0.625.
    const Moment moments[] = {
        {0.0, node0(0, 0, 1), make_translate(Vec3{0, 5, 0})},
        {0.5, node0(1, 22.5f, 1), make_translate(Vec3{0.625f, 5, 0})},
        {1.0, node0(2, 45, 2), make_translate(Vec3{0.75f, 5, 0})},
        {5.0, node0(4, 90, 2), make_translate(Vec3{1, 5, 0})},
        {-1.0, node0(0, 0, 1), make_translate(Vec3{0, 5, 0})},
    };
    for (const Moment& m : moments) {
        SCOPED_TRACE(m.time);
        set_scene_time(scene, m.time, "scene");
        expect_near(scene.instances[0].object_to_world, m.node0);
        expect_near(scene.instances[1].object_to_world, compose(child, m.node0));  // moves with its parent
        expect_near(scene.instances[2].object_to_world, m.node2);
    }
    EXPECT_EQ(fuzz::scene_problem(s), "");
}

TEST(GltfAnimation, TheLoaderKeepsAnimatedMeshesAsPartsPlacedAtTimeZero) {
    TempFolder dir;
    const std::filesystem::path path = dir.path / "m.gltf";
    animated_file().save(path);
    Diagnostics diag;
    const LoadedMesh loaded = load_gltf(path, diag);
    ASSERT_TRUE(loaded.animation);
    EXPECT_EQ(loaded.animation->end_time, 2.0);
    EXPECT_EQ(loaded.mesh.triangle_count(), 6u);
    ASSERT_EQ(loaded.instanced.size(), 2u);
    EXPECT_EQ(loaded.instanced[1].instances.size(), 1u);
    EXPECT_EQ(loaded.instanced[1].nodes, std::vector<std::uint32_t>{2});
    // Time 0, not the rest pose (9, 9, 9).
    expect_near(loaded.instanced[1].instances[0], make_translate(Vec3{0, 5, 0}));
    EXPECT_EQ(fuzz::loaded_mesh_problem(loaded), "");
}

TEST(GltfAnimation, RotationsMayBeNormalizedShortsAndAreNormalised) {
    GltfFile f;
    add_pyramid(f);
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    const std::vector<std::int16_t> q{0, 0, 0, 32767, 0, 16000, 0, 16000};  // 0° and 90° about y, not unit
    const int in = f.add_array(std::vector<float>{0, 1}, kFloat, 2, "SCALAR");
    const int out = f.add_array(q, kShort, 2, "VEC4", true);
    f.doc["animations"][0]["samplers"].push_back({{"input", in}, {"output", out}});  // LINEAR by default
    add_channel(f, 0, 0, "rotation");
    TempFolder dir;
    Diagnostics diag;
    LoadedScene s = quick_look(f, dir, diag);
    set_scene_time(s.scene, 0.5, "scene");
    expect_near(s.scene.instances[0].object_to_world, make_rotate(Vec3{0, 1, 0}, 45));
}

TEST(GltfAnimation, GpuInstancesActBeforeTheirAnimatedNode) {
    GltfFile f =
        gltf_test::instancing::gpu_instanced_file();  // node 0 at rest: translation (0, 0, -1), scale (1, 2, 1)
    add_channel(f, add_sampler(f, {0, 1}, {0, 0, -1, 0, 4, -1}, "VEC3", "LINEAR"), 0, "translation");
    TempFolder dir;
    Diagnostics diag;
    LoadedScene s = quick_look(f, dir, diag);
    ASSERT_EQ(s.scene.instances.size(), std::size_t(gltf_test::kInstances));
    set_scene_time(s.scene, 0.5, "scene");
    const Transform node = compose(make_scale(Vec3{1, 2, 1}), make_translate(Vec3{0, 2, -1}));
    for (int k = 0; k < gltf_test::kInstances; ++k) {
        SCOPED_TRACE(k);
        const gltf_test::instancing::Trs trs = gltf_test::instancing::instance_trs(k);
        const std::optional<Transform> local =
            gltf::trs_transform(trs.t, trs.q[0], trs.q[1], trs.q[2], trs.q[3], trs.s);
        ASSERT_TRUE(local);
        expect_near(s.scene.instances[std::size_t(k)].object_to_world, compose(*local, node), 1e-5f);
        EXPECT_EQ(s.scene.instances[std::size_t(k)].mirrored, k == 3);
    }
}

TEST(GltfAnimation, AnObjectsTransformActsAfterTheNodesAndTheSceneStartsAtItsFirstFrame) {
    TempFolder dir;
    animated_file().save(dir.path / "m.gltf");
    dir.write("s.json", R"({"camera": {"origin": [0, 0, 9], "look_at": [0, 0, 0]},
        "animation": {"fps": 2, "frames": [2, 10]},
        "objects": [{"file": "m.gltf", "transform": [{"translate": [0, -1, 0]}],
                     "instances": [[{"translate": [0, 0, 0]}], [{"translate": [10, 0, 0]}]]}]})");
    Diagnostics diag;
    LoadedScene s = load_scene_file(dir.path / "s.json", diag);
    Scene& scene = s.scene;
    // The static mesh twice, then (nodes 0 and 1 drawing mesh 0) × 2, then node 2 × 2.
    ASSERT_EQ(scene.instances.size(), 8u);
    const Transform object = make_translate(Vec3{0, -1, 0}), second = make_translate(Vec3{10, 0, 0});
    // Frame 2 at 2 fps: 1 s.
    expect_near(scene.instances[2].object_to_world, compose(node0(2, 45, 2), object));
    expect_near(scene.instances[4].object_to_world, compose(compose(node0(2, 45, 2), object), second), 1e-4f);
    expect_near(scene.instances[7].object_to_world,
                compose(compose(make_translate(Vec3{0.75f, 5, 0}), object), second));
    set_scene_time(scene, 5.0, "s.json");
    expect_near(scene.instances[3].object_to_world,
                compose(compose(make_translate(Vec3{0, 3, 0}), node0(4, 90, 2)), object), 1e-4f);
    EXPECT_EQ(fuzz::scene_problem(s), "");
}

TEST(GltfAnimation, AKeyedObjectTransformActsAfterTheNodesOnTheSameClock) {
    TempFolder dir;
    animated_file().save(dir.path / "m.gltf");
    dir.write("s.json", R"({"camera": {"origin": [0, 0, 9], "look_at": [0, 0, 0]},
        "objects": [{"file": "m.gltf", "transform": {"keys": [
            {"time": 0, "transform": [{"translate": [0, 0, 0]}]},
            {"time": 2, "transform": [{"translate": [0, 10, 0]}]}]}}]})");
    Diagnostics diag;
    LoadedScene s = load_scene_file(dir.path / "s.json", diag);
    Scene& scene = s.scene;
    ASSERT_EQ(scene.instances.size(), 4u);  // the static mesh (keyed), nodes 0 and 1, node 2
    expect_near(scene.instances[1].object_to_world, node0(0, 0, 1));
    expect_near(scene.instances[3].object_to_world, make_translate(Vec3{0, 5, 0}));
    set_scene_time(scene, 1.0, "s.json");
    expect_near(scene.instances[0].object_to_world, make_translate(Vec3{0, 5, 0}));  // its vertices in the file's world
    expect_near(scene.instances[1].object_to_world, compose(node0(2, 45, 2), make_translate(Vec3{0, 5, 0})));
    expect_near(scene.instances[3].object_to_world, make_translate(Vec3{0.75f, 10, 0}));
}

TEST(GltfAnimation, WeightsChannelsAreSkippedWithOneWarning) {
    GltfFile f = animated_file();
    const int weights = add_sampler(f, {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", "LINEAR");
    add_channel(f, weights, 0, "weights");
    add_channel(f, weights, 2, "weights");
    TempFolder dir;
    Diagnostics diag;
    quick_look(f, dir, diag);
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("morph target weights (2)"), std::string::npos) << diag.warnings[0];
}

TEST(GltfAnimation, AFileWithoutAnimationsLoadsAsBefore) {
    GltfFile f = animated_file();
    f.doc.erase("animations");
    TempFolder dir;
    Diagnostics diag;
    const LoadedScene s = quick_look(f, dir, diag);
    EXPECT_FALSE(s.scene.animation);
    EXPECT_EQ(s.scene.instances.size(), 2u);  // mesh 0, which nodes 0 and 1 draw; the others flattened
    EXPECT_EQ(s.scene.geometry.triangle_count(), 12u);
    for (const InstancedPart& part : load_gltf(dir.path / "m.gltf", diag).instanced) EXPECT_TRUE(part.nodes.empty());
}

struct HostileCase {
    const char* name;
    std::function<void(GltfFile&)> edit;
    const char* message_part;
};

// Overwrites accessor `a`'s data with `values` (same size).
void overwrite(GltfFile& f, int a, const std::vector<float>& values) {
    const std::size_t offset = f.doc["bufferViews"][f.doc["accessors"][a]["bufferView"].get<int>()]["byteOffset"];
    std::memcpy(f.bin.data() + offset, values.data(), values.size() * sizeof(float));
}
int input_of(GltfFile& f, int sampler) { return f.doc["animations"][0]["samplers"][sampler]["input"]; }
int output_of(GltfFile& f, int sampler) { return f.doc["animations"][0]["samplers"][sampler]["output"]; }

const HostileCase kHostile[] = {
    {"times not increasing",
     [](GltfFile& f) {
         overwrite(f, input_of(f, 0), {1, 1});
     },
     "animation 0: sampler 0: key times must increase"},
    {"time not finite",
     [](GltfFile& f) {
         overwrite(f, input_of(f, 1), {0, NAN});
     },
     "(animation 0: sampler 1 input): element 1 is not finite"},
    {"value NaN",
     [](GltfFile& f) {
         overwrite(f, output_of(f, 0), {0, 0, 0, 4, NAN, 0});
     },
     "(animation 0: sampler 0 output): element 1 is not finite"},
    {"output count", [](GltfFile& f) { f.doc["accessors"][output_of(f, 0)]["count"] = 1; },
     "animation 0: sampler 0: the output has 1 elements for 2 key times"},
    {"cubic output count", [](GltfFile& f) { f.doc["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE"; },
     "animation 0: sampler 0: the output has 2 elements for 2 key times (CUBICSPLINE needs 3 per key)"},
    {"missing node", [](GltfFile& f) { f.doc["animations"][0]["channels"][1]["target"]["node"] = 99; },
     "animation 0: channel 1: targets node 99, but the file has 4 nodes"},
    {"missing sampler", [](GltfFile& f) { f.doc["animations"][0]["channels"][2]["sampler"] = 7; },
     "animation 0: channel 2: sampler 7 does not exist"},
    {"unknown interpolation", [](GltfFile& f) { f.doc["animations"][0]["samplers"][2]["interpolation"] = "QUADRATIC"; },
     "animation 0: sampler 2: unknown interpolation 'QUADRATIC'"},
    {"unknown path", [](GltfFile& f) { f.doc["animations"][0]["channels"][0]["target"]["path"] = "colour"; },
     "animation 0: channel 0: unknown target path 'colour'"},
    {"translation as VEC4", [](GltfFile& f) { f.doc["animations"][0]["channels"][0]["sampler"] = 1; },
     "(animation 0: sampler 1 output): type VEC4 where VEC3 is expected"},
    {"integer times",
     [](GltfFile& f) { f.doc["accessors"][input_of(f, 0)]["componentType"] = gltf_test::kUnsignedInt; },
     "(animation 0: sampler 0 input): UNSIGNED_INT components are not allowed here"},
    {"a matrix node animated",
     [](GltfFile& f) { f.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
     "animation 0: channel 0: node 0 has a matrix"},
    {"zero quaternion",
     [](GltfFile& f) {
         overwrite(f, output_of(f, 1), {0, 0, 0, 0, 0, kS45, 0, kC45});
     },
     "animation 0: sampler 1: key 0 is not a unit quaternion"},
    {"a count of 2^62, counted before it is read",
     [](GltfFile& f) { f.doc["accessors"][output_of(f, 0)]["count"] = std::size_t{1} << 62; },
     "animation 0: sampler 0: the file's animations hold more than 67108864 key values"},
    {"channel not an object", [](GltfFile& f) { f.doc["animations"][0]["channels"][0] = 3; },
     "/animations/0/channels/0"},
};

TEST(GltfAnimation, HostileAnimationsAreOneErrorLine) {
    for (const HostileCase& c : kHostile) {
        SCOPED_TRACE(c.name);
        GltfFile f = animated_file();
        c.edit(f);
        TempFolder dir;
        const std::filesystem::path path = dir.path / "m.gltf";
        f.save(path);
        try {
            Diagnostics diag;
            load_gltf(path, diag);
            ADD_FAILURE() << "loaded";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(c.message_part), std::string::npos) << what;
            EXPECT_NE(what.find("m.gltf"), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

}  // namespace
}  // namespace sombra
