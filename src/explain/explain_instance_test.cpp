// `sombra explain` names the instance of a sampled emitter (spec §23): an
// emissive quad drawn as three instances lights a floor, and the emitter a
// light sample picked is named by its object, its instance and its mesh
// triangle, in the text and in the JSON alike.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "explain/describe.h"
#include "explain/explain.h"
#include "render/test_meshes.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

Scene floor_under_three_lamps() {
    SceneBuilder b;
    TriangleMesh floor, lamp;
    testing::add_quad(floor, {-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, 0);
    testing::add_quad(lamp, {-0.3f, 0, -0.3f}, {-0.3f, 0, 0.3f}, {0.3f, 0, 0.3f}, {0.3f, 0, -0.3f}, 0);
    const std::vector<Material> grey{Material{"floor", MaterialType::Diffuse, Vec3{0.5f}}};
    Material glow{"glow", MaterialType::Diffuse, Vec3{0.0f}};
    glow.ke = Vec3{5.0f};
    EXPECT_EQ(b.add_mesh(floor, grey, {}, MeshPlacement{"/objects/0", "floor.obj", std::nullopt, std::nullopt}),
              MeshProblem::None);
    const std::vector<Transform> placements{make_translate({-1, 1.5f, 0}), make_translate({0, 1.5f, 0}),
                                            compose(make_scale({-1, 1, 1}), make_translate({1, 1.5f, 0}))};
    EXPECT_EQ(b.add_instanced_mesh(lamp, std::vector<Material>{glow}, {},
                                   MeshPlacement{"/objects/1", "lamp.obj", std::nullopt, std::nullopt}, placements),
              MeshProblem::None);
    CameraSpec camera;
    camera.look_at = CameraLookAt{{0, 1, 3}, {0, 0, 0}, {0, 1, 0}, 40};
    b.set_camera(camera);
    return b.finish();
}

TEST(ExplainInstance, NamesTheInstanceOfASampledEmitter) {
    const Scene scene = floor_under_three_lamps();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    RenderSettings settings{8, 8, 4, 0};
    settings.integrator = IntegratorKind::Path;
    settings.max_depth = 1;
    const RenderJob job = make_render_job(scene, accel, settings, 1);
    const ExplainContext context{scene, job, "test.json"};
    std::vector<bool> instance_named(3, false);
    for (int j = 4; j < 8; ++j)  // the lower half: the floor
        for (int i = 0; i < 8; ++i)
            for (int k = 0; k < settings.spp; ++k) {
                SampleRecord record;
                RayCounters counters;
                trace_pixel_sample(job, i, j, k, counters, record);
                ASSERT_FALSE(record.vertices.empty());
                const SampledLightRecord& l = record.vertices[0].sampled_light;
                if (!l.sampled || l.environment) continue;
                ASSERT_LT(l.instance, 3u) << "every emitter lies in an instance";
                ASSERT_LT(l.triangle, 2u) << "a triangle of the lamp mesh";
                instance_named[l.instance] = true;
                const std::string words = "sampled light " + std::to_string(l.light) +
                                          ": /objects/1 (lamp.obj), instance " + std::to_string(l.instance) +
                                          ", triangle " + std::to_string(l.triangle);
                const std::string text = explain_text(context, record);
                EXPECT_NE(text.find(words), std::string::npos) << text;
                const nlohmann::json json = nlohmann::json::parse(explain_json(context, record));
                // The first vertex's lights: no delta lights, so the sampled one alone.
                ASSERT_EQ(json["lights"].size(), 1u) << json.dump();
                const nlohmann::json& emitter = json["lights"][0]["emitter"];
                EXPECT_EQ(emitter["object"], "/objects/1") << json.dump();
                EXPECT_EQ(emitter["instance"], l.instance) << json.dump();
                EXPECT_EQ(emitter["triangle"], l.triangle) << json.dump();
                EXPECT_FALSE(emitter.contains("scene_triangle")) << json.dump();
            }
    for (std::size_t k = 0; k < 3; ++k) EXPECT_TRUE(instance_named[k]) << "no sample picked instance " << k;
}

}  // namespace
}  // namespace sombra
