// Lights and cameras that glTF nodes carry follow the nodes' animation
// (spec §22: "glTF animations drive their nodes"), in the quick look and in
// scene files (after the object's transform and its instances), as do the
// lights of a scene object whose transform is keyed; positions and
// directions against ones computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../../../fuzz/fuzz_harness.h"
#include "core/error.h"
#include "io/gltf/gltf_test_files.h"
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
using testing::TempFolder;

void add_animation(GltfFile& f, int node, const char* path, const std::vector<float>& times,
                   const std::vector<float>& values, const char* type, const char* interpolation = "LINEAR") {
    const std::size_t width = std::string(type) == "VEC4" ? 4 : 3;
    const int in = f.add_array(times, kFloat, times.size(), "SCALAR");
    const int out = f.add_array(values, kFloat, values.size() / width, type);
    auto& animation = f.doc["animations"][0];
    animation["samplers"].push_back({{"input", in}, {"output", out}, {"interpolation", interpolation}});
    const int sampler = int(animation["samplers"].size()) - 1;
    animation["channels"].push_back({{"sampler", sampler}, {"target", {{"node", node}, {"path", path}}}});
}

const float kS45 = std::sin(0.25f * 3.14159265f), kC45 = std::cos(0.25f * 3.14159265f);

// A static pyramid (node 0); a rig (node 1) carrying the camera and a
// directional light, moving (0, 0, 5) → (4, 0, 5) and turning 0° → 90°
// about y over 0..2 s; its child (node 2), 1 above it, a point light.
// Nothing that draws triangles moves.
GltfFile rig_file() {
    GltfFile f;
    add_pyramid(f);
    f.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
    f.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1, 1, 1}}, {"intensity", 10}},
        {{"type", "directional"}, {"color", {1, 1, 1}}, {"intensity", 2}}};
    f.use_extension("KHR_lights_punctual");
    f.add_node({{"mesh", 0}, {"translation", {0, 0, -7}}});
    f.add_node({{"camera", 0},
                {"children", {2}},
                {"translation", {0, 0, 5}},
                {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    f.add_node({{"translation", {0, 1, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    f.set_scene({0, 1});
    add_animation(f, 1, "translation", {0, 2}, {0, 0, 5, 4, 0, 5}, "VEC3");
    add_animation(f, 1, "rotation", {0, 2}, {0, 0, 0, 1, 0, kS45, 0, kC45}, "VEC4");
    return f;
}

void expect_near(Vec3 got, Vec3 want, float tolerance = 1e-5f) {
    EXPECT_NEAR(got.x, want.x, tolerance);
    EXPECT_NEAR(got.y, want.y, tolerance);
    EXPECT_NEAR(got.z, want.z, tolerance);
}

// The view direction of the rig's camera (its −z) after turning `degrees` about y.
Vec3 rig_forward(float degrees) {
    const float a = degrees * 3.14159265f / 180.0f;
    return {-std::sin(a), 0.0f, -std::cos(a)};
}

TEST(GltfAnimatedLights, TheQuickLooksCameraAndLightsFollowTheirNodes) {
    TempFolder dir;
    rig_file().save(dir.path / "m.gltf");
    Diagnostics diag;
    LoadedScene s = make_quicklook_scene(dir.path / "m.gltf", diag);
    Scene& scene = s.scene;
    // Only the camera and lights move, and that is animation enough.
    ASSERT_TRUE(scene.animation);
    EXPECT_EQ(scene.animation->last_frame, 48);
    EXPECT_TRUE(scene.instances.empty());
    ASSERT_EQ(scene.lights.size(), 2u);  // the file's, no automatic ones
    ASSERT_TRUE(scene.camera.look_at);
    const float fov = scene.camera.look_at->fov_degrees;
    // Time 0 places the camera and lights exactly as the loader did.
    const CameraLookAt loaded = *scene.camera.look_at;
    const std::vector<PunctualLight> loaded_lights = scene.lights;
    set_scene_time(scene, 0.0, "m.gltf");
    EXPECT_EQ(scene.camera.look_at->origin, loaded.origin);
    EXPECT_EQ(scene.camera.look_at->look_at, loaded.look_at);
    EXPECT_EQ(scene.camera.look_at->up, loaded.up);
    for (std::size_t i = 0; i < loaded_lights.size(); ++i) {
        EXPECT_EQ(scene.lights[i].position, loaded_lights[i].position) << i;
        EXPECT_EQ(scene.lights[i].direction, loaded_lights[i].direction) << i;
    }
    struct Moment {
        double time;
        float x, degrees;
    };
    for (const Moment m : {Moment{0.0, 0, 0}, Moment{1.0, 2, 45}, Moment{2.0, 4, 90}, Moment{7.0, 4, 90}}) {
        SCOPED_TRACE(m.time);
        set_scene_time(scene, m.time, "m.gltf");
        const CameraLookAt& view = *scene.camera.look_at;
        expect_near(view.origin, {m.x, 0, 5});
        expect_near(view.look_at - view.origin, rig_forward(m.degrees));
        expect_near(view.up, {0, 1, 0});
        EXPECT_EQ(view.fov_degrees, fov);
        // The point light on the child, 1 above the rig (a turn about y leaves it there).
        const PunctualLight& point = scene.lights[0].type == LightType::Point ? scene.lights[0] : scene.lights[1];
        const PunctualLight& sun = scene.lights[0].type == LightType::Point ? scene.lights[1] : scene.lights[0];
        expect_near(point.position, {m.x, 1, 5});
        expect_near(sun.direction, rig_forward(m.degrees));  // KHR lights shine along their node's −z
    }
    EXPECT_EQ(fuzz::scene_problem(s), "");
}

TEST(GltfAnimatedLights, InAScenesFileTheyFollowTheNodeThenTheObjectAndItsInstances) {
    TempFolder dir;
    rig_file().save(dir.path / "m.gltf");
    dir.write("s.json", R"({"camera": {"origin": [0, 0, 30], "look_at": [0, 0, 0]},
        "objects": [{"file": "m.gltf", "transform": [{"translate": [0, -1, 0]}],
                     "instances": [[{"translate": [0, 0, 0]}], [{"translate": [10, 0, 0]}]]}]})");
    Diagnostics diag;
    LoadedScene s = load_scene_file(dir.path / "s.json", diag);
    Scene& scene = s.scene;
    ASSERT_TRUE(scene.animation);
    ASSERT_EQ(scene.lights.size(), 4u);  // two lights, each in both instances
    set_scene_time(scene, 1.0, "s.json");
    std::vector<Vec3> points;
    for (const PunctualLight& l : scene.lights) {
        if (l.type == LightType::Point) {
            points.push_back(l.position);
        } else {
            expect_near(l.direction, rig_forward(45));
        }
    }
    ASSERT_EQ(points.size(), 2u);
    expect_near(points[0], {2, 0, 5});
    expect_near(points[1], {12, 0, 5});
    // The scene file's own camera does not follow the file's.
    expect_near(scene.camera.look_at->origin, {0, 0, 30});
}

TEST(GltfAnimatedLights, AKeyedObjectCarriesTheLightsOfAStaticFile) {
    GltfFile f = rig_file();
    f.doc.erase("animations");
    TempFolder dir;
    f.save(dir.path / "m.gltf");
    dir.write("s.json", R"({"camera": {"origin": [0, 0, 30], "look_at": [0, 0, 0]},
        "objects": [{"file": "m.gltf", "transform": {"keys": [
            {"time": 0, "transform": [{"translate": [0, 0, 0]}]},
            {"time": 2, "transform": [{"rotate": {"axis": [0, 1, 0], "degrees": 90}}, {"translate": [0, 10, 0]}]}]}}]})");
    Diagnostics diag;
    LoadedScene s = load_scene_file(dir.path / "s.json", diag);
    Scene& scene = s.scene;
    ASSERT_EQ(scene.lights.size(), 2u);
    const std::size_t point = scene.lights[0].type == LightType::Point ? 0 : 1;
    expect_near(scene.lights[point].position, {0, 1, 5});
    set_scene_time(scene, 2.0, "s.json");
    // (0, 1, 5) turned 90° about y is (5, 1, 0); then 10 up.
    expect_near(scene.lights[point].position, {5, 11, 0}, 1e-4f);
    expect_near(scene.lights[1 - point].direction, rig_forward(90));
}

TEST(GltfAnimatedLights, ACameraNodeScaledToNothingIsOneError) {
    GltfFile f = rig_file();
    f.doc["nodes"][1].erase("extensions");  // the camera alone on the node (its child's point light stays finite)
    add_animation(f, 1, "scale", {0, 1}, {1, 1, 1, 0, 0, 0}, "VEC3", "STEP");
    TempFolder dir;
    f.save(dir.path / "m.gltf");
    Diagnostics diag;
    LoadedScene s = make_quicklook_scene(dir.path / "m.gltf", diag);
    set_scene_time(s.scene, 0.5, "m.gltf");
    try {
        set_scene_time(s.scene, 1.5, "m.gltf");
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("m.gltf"), std::string::npos) << message;
        EXPECT_NE(message.find("node 1"), std::string::npos) << message;
        EXPECT_NE(message.find("1.5"), std::string::npos) << message;
        EXPECT_NE(message.find("camera"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace sombra
