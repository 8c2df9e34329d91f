// `sombra explain` tells the truth: the value it reports is the render's,
// bit for bit, and the terms it lists add up to that value, for a thousand
// random pixels of every shared scene under both integrators.
#include "explain/explain.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "explain/describe.h"
#include "io/scene_json/scene_file.h"
#include "render/test_meshes.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

const std::filesystem::path kShared = SOMBRA_SHARED_DIR;
const std::filesystem::path kSource = SOMBRA_SOURCE_DIR;

bool same_bits(Vec3 a, Vec3 b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::string show(Vec3 v) { return exact(v); }

// The terms a record lists, added in the order the integrator added them.
Vec3 sum_of_terms(const SampleRecord& r) {
    Vec3 sum{0.0f};
    for (const VertexRecord& v : r.vertices) {
        if (v.emission.present) sum += v.emission.contribution;
        for (const DeltaLightRecord& l : v.delta_lights) sum += l.contribution;
        if (v.sampled_light.sampled) sum += v.sampled_light.contribution;
    }
    return sum;
}

// Renders `scene` at `settings`, then re-traces `pixel_count` random pixels'
// every sample with the recorder: each pixel's average must be the film's
// value to the last bit, and each sample's terms must add up to its value.
void expect_explain_matches_render(const Scene& scene, const RenderSettings& settings, int pixel_count,
                                   const char* what) {
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, settings, 2);
    RenderProgress progress;
    const RenderOutput out = render_image(job, progress);
    ASSERT_FALSE(out.cancelled);

    std::mt19937 rng(12345);
    std::uniform_int_distribution<int> column(0, settings.width - 1), row(0, settings.height - 1);
    int mismatches = 0, unbalanced = 0, with_terms = 0;
    for (int n = 0; n < pixel_count; ++n) {
        const int i = column(rng), j = row(rng);
        Vec3 sum{0.0f};
        for (int k = 0; k < settings.spp; ++k) {
            SampleRecord record;
            RayCounters counters;
            const Vec3 value = trace_pixel_sample(job, i, j, k, counters, record);
            EXPECT_TRUE(same_bits(value, record.value));
            EXPECT_EQ(record.pixel_x, i);
            EXPECT_EQ(record.sample, k);
            if (!record.nonfinite) {
                with_terms += max_component(value) > 0.0f;
                if (!same_bits(sum_of_terms(record), value) && ++unbalanced <= 3)
                    ADD_FAILURE() << what << " pixel (" << i << ", " << j << ") sample " << k << ": terms add to "
                                  << show(sum_of_terms(record)) << ", value " << show(value);
            }
            sum += value;
        }
        const Vec3 pixel = sum / static_cast<float>(settings.spp);
        if (!same_bits(pixel, out.film.at(i, j)) && ++mismatches <= 3)
            ADD_FAILURE() << what << " pixel (" << i << ", " << j << "): explain " << show(pixel) << ", render "
                          << show(out.film.at(i, j));
    }
    EXPECT_EQ(mismatches, 0) << what;
    EXPECT_EQ(unbalanced, 0) << what;
    EXPECT_GT(with_terms, pixel_count / 10) << what << ": too few lit samples for the check to mean anything";
}

RenderSettings scaled_down(const RenderSettings& s, int factor, IntegratorKind integrator, int spp) {
    RenderSettings r = s;
    r.width = std::max(1, s.width / factor);
    r.height = std::max(1, s.height / factor);
    r.integrator = integrator;
    r.spp = spp;
    return r;
}

class ExplainSharedScene : public ::testing::TestWithParam<const char*> {};

TEST_P(ExplainSharedScene, ValueIsTheRenderedSampleBitForBit) {
    const std::filesystem::path file = kShared / "scenes" / GetParam();
    if (!std::filesystem::exists(file))
        GTEST_SKIP() << "shared/ not found at " << kShared << ": " << file << " is missing";
    Diagnostics diag;
    const auto [scene, file_settings] = load_scene_file(file, diag);
    expect_explain_matches_render(scene, scaled_down(file_settings, 8, IntegratorKind::Direct, 1), 1000,
                                  "direct, 1 spp");
    expect_explain_matches_render(scene, scaled_down(file_settings, 8, IntegratorKind::Path, 3), 1000, "path, 3 spp");
}

INSTANTIATE_TEST_SUITE_P(SharedScenes, ExplainSharedScene,
                         ::testing::Values("bunny.json", "cornell.json", "phong.json", "manylights.json",
                                           "dragon.json"));

// The repository's scene of spot, sun and thin lens (spec §16, §17), under
// both integrators: every delta light's factor and every lens sample.
TEST(ExplainRepoScene, SpotSunAndLensMatchTheRender) {
    Diagnostics diag;
    const auto [scene, file_settings] = load_scene_file(kSource / "scenes" / "spot-sun-dof.json", diag);
    expect_explain_matches_render(scene, scaled_down(file_settings, 8, IntegratorKind::Direct, 3), 1000,
                                  "direct, 3 spp");
    expect_explain_matches_render(scene, scaled_down(file_settings, 8, IntegratorKind::Path, 3), 1000, "path, 3 spp");
}

// The repository's path-tracing scenes: quad lights (MIS), glass, metal, Russian roulette.
TEST(ExplainRepoScene, PathTracedScenesMatchTheRender) {
    for (const char* name : {"cornell-box-path.json", "spheres.json", "cutouts.json"}) {
        Diagnostics diag;
        const auto [scene, file_settings] = load_scene_file(kSource / "scenes" / name, diag);
        expect_explain_matches_render(scene, scaled_down(file_settings, 8, IntegratorKind::Path, 4), 1000, name);
    }
}

TEST(ExplainRecord, ListsTheCutOutsARayWentThrough) {
    // The perforated screen of scenes/cutouts.json: camera rays through its
    // holes record each crossing, nearer than what they hit, with alpha
    // below the cutoff; the first crossing is what the ray would hit if the
    // screen had no holes.
    Diagnostics diag;
    const auto [scene, file_settings] = load_scene_file(kSource / "scenes" / "cutouts.json", diag);
    const RenderSettings settings = scaled_down(file_settings, 8, IntegratorKind::Direct, 1);
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const Accel solid = make_accel(scene.geometry, AccelKind::Bvh);  // the same surfaces without cut-outs
    const RenderJob job = make_render_job(scene, accel, settings, 1);
    int through = 0, lit_through = 0;
    for (int j = 0; j < settings.height; ++j)
        for (int i = 0; i < settings.width; ++i) {
            SampleRecord record;
            RayCounters counters;
            trace_pixel_sample(job, i, j, 0, counters, record);
            ASSERT_FALSE(record.vertices.empty());
            const VertexRecord& v = record.vertices[0];
            ASSERT_EQ(v.holes.size(), v.holes_crossed);
            // Shadow rays that reach the lamp through a hole list it too, nearer than the lamp.
            for (const DeltaLightRecord& l : v.delta_lights) {
                if (l.outcome != LightOutcome::Visible || l.holes_crossed == 0) continue;
                ++lit_through;
                EXPECT_EQ(scene.materials[scene.geometry.material_ids[l.holes[0].triangle]].name, "screen");
                EXPECT_LT(l.holes[0].alpha, l.holes[0].cutoff);
                EXPECT_GT(l.holes[0].t, 0.0f);
                EXPECT_LT(l.holes[0].t, 1.0f) << "the shadow ray runs from x to just before the light";
            }
            if (v.holes_crossed == 0) continue;
            ++through;
            const HoleRecord& hole = v.holes[0];
            EXPECT_EQ(scene.materials[scene.geometry.material_ids[hole.triangle]].name, "screen");
            EXPECT_LT(hole.alpha, hole.cutoff);
            if (v.hit) {
                EXPECT_LT(hole.t, v.surface.t);
            }
            Hit first;
            ASSERT_TRUE(intersect(solid, Ray{record.origin, record.direction}, first));
            EXPECT_EQ(first.triangle, hole.triangle);
            EXPECT_EQ(first.t, hole.t);
        }
    EXPECT_GT(through, 50) << "the screen's holes cover a good part of the picture";
    EXPECT_GT(lit_through, 20) << "and the lamp lights the wall through them";
}

// A ground quad (object 0) under a small blocker quad (object 1), lit by two
// point lights: one straight above (blocked), one below the ground (behind),
// seen by a 1×1 camera from the side, looking past the blocker at the ground in its shadow.
Scene blocked_scene() {
    SceneBuilder b;
    TriangleMesh ground, blocker;
    testing::add_quad(ground, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, 0);
    testing::add_quad(blocker, {-0.5f, 1, -0.5f}, {-0.5f, 1, 0.5f}, {0.5f, 1, 0.5f}, {0.5f, 1, -0.5f}, 0);
    const std::vector<Material> grey{Material{"ground", MaterialType::Diffuse, Vec3{0.5f}}};
    const std::vector<Material> dark{Material{"blocker", MaterialType::Diffuse, Vec3{0.2f}}};
    EXPECT_EQ(b.add_mesh(ground, grey, {}, MeshPlacement{"/objects/0", "ground.obj", std::nullopt, std::nullopt}),
              MeshProblem::None);
    EXPECT_EQ(b.add_mesh(blocker, dark, {}, MeshPlacement{"/objects/1", "blocker.obj", std::nullopt, std::nullopt}),
              MeshProblem::None);
    for (const PunctualLight& light :
         {make_point_light({0, 3, 0}, Vec3{10.0f}), make_point_light({0, -1, 0}, Vec3{10.0f}),
          make_point_light({1.5f, 2, 0}, Vec3{8.0f})})
        b.add_light(light);
    CameraSpec camera;
    camera.look_at = CameraLookAt{{3, 2, 0.1f}, {0.1f, 0, 0.1f}, {0, 1, 0}, 10};
    b.set_camera(camera);
    return b.finish();
}

// The blocked scene's one pixel, traced with the recorder.
struct BlockedStory {
    Scene scene;
    Accel accel = make_accel(scene, AccelKind::Bvh);
    RenderJob job = make_render_job(scene, accel, RenderSettings{1, 1, 1, 0}, 1);
    SampleRecord record;
    explicit BlockedStory(Scene s = blocked_scene()) : scene(std::move(s)) {
        RayCounters counters;
        trace_pixel_sample(job, 0, 0, 0, counters, record);
    }
};

TEST(ExplainRecord, NamesTheBlockerTheLightBehindAndEachFactorOfTheVisibleLight) {
    const BlockedStory story;
    const Scene& scene = story.scene;
    const RenderJob& job = story.job;
    const SampleRecord& r = story.record;

    ASSERT_EQ(r.vertices.size(), 1u);
    const VertexRecord& v = r.vertices[0];
    ASSERT_TRUE(v.hit);
    EXPECT_LT(v.surface.triangle, 2u);  // the ground
    EXPECT_NEAR(v.surface.distance, std::sqrt(2.9f * 2.9f + 4.0f), 1e-4f);
    ASSERT_EQ(v.delta_lights.size(), 3u);

    const DeltaLightRecord& above = v.delta_lights[0];
    EXPECT_EQ(above.outcome, LightOutcome::Blocked);
    EXPECT_TRUE(above.blocker.triangle == 2 || above.blocker.triangle == 3) << above.blocker.triangle;
    // The blocker is 1 above the ground: the ray to (0, 3, 0) meets it a third of its way up.
    EXPECT_NEAR(above.blocker.distance, length(Vec3{-0.1f, 3, -0.1f}) / 3.0f, 1e-4f);
    EXPECT_EQ(above.contribution, Vec3{0.0f});

    EXPECT_EQ(v.delta_lights[1].outcome, LightOutcome::Behind);

    // The visible light: each factor as spec §4 writes it.
    const DeltaLightRecord& side = v.delta_lights[2];
    ASSERT_EQ(side.outcome, LightOutcome::Visible);
    const Vec3 to_light = scene.lights[2].position - v.surface.position;
    const float d2 = dot(to_light, to_light);
    EXPECT_NEAR(side.distance, std::sqrt(d2), 1e-5f);
    EXPECT_NEAR(side.incident.x, 8.0f / d2, 1e-5f);
    EXPECT_NEAR(side.f_terms.diffuse.x, 0.5f / 3.14159265f, 1e-6f);
    EXPECT_EQ(side.f_terms.lobe, Vec3{0.0f});
    EXPECT_NEAR(side.cos_s, to_light.y / std::sqrt(d2), 1e-5f);
    EXPECT_NEAR(side.contribution.x, side.incident.x * side.f.x * side.cos_s, 1e-6f);
    EXPECT_TRUE(same_bits(r.value, side.contribution));

    // The text and the JSON say the same.
    const ExplainContext context{scene, job, "test.json"};
    const std::string text = explain_text(context, r);
    EXPECT_NE(text.find("BLOCKED: the shadow ray meets /objects/1 (blocker.obj)"), std::string::npos) << text;
    EXPECT_NE(text.find("BEHIND"), std::string::npos) << text;
    const nlohmann::json j = nlohmann::json::parse(explain_json(context, r));
    EXPECT_EQ(j["pixel"], nlohmann::json::array({0, 0}));
    EXPECT_EQ(j["sample"], 0);
    EXPECT_EQ(j["hit"]["object"], "/objects/0");
    EXPECT_EQ(j["lights"][0]["outcome"], "blocked");
    EXPECT_EQ(j["lights"][0]["blocker"]["object"], "/objects/1");
    EXPECT_EQ(j["lights"][1]["outcome"], "behind");
    EXPECT_EQ(j["lights"][2]["outcome"], "visible");
    // "value" reads back to the very floats.
    const Vec3 value{static_cast<float>(j["value"][0].get<double>()), static_cast<float>(j["value"][1].get<double>()),
                     static_cast<float>(j["value"][2].get<double>())};
    EXPECT_TRUE(same_bits(value, r.value));
}

// A glTF pbr with a rough thin-wall transmission and a clearcoat: the light
// below the ground now shines through it (the transmission term), the
// visible light above shows the coat; text and JSON name both terms.
TEST(ExplainRecord, NamesThePbrTransmissionAndCoatTerms) {
    Scene scene = blocked_scene();
    for (Material& m : scene.materials) {
        m.type = MaterialType::Pbr;
        m.base_color = Vec3{0.6f};
        m.roughness = 0.5f;
        m.transmission = 0.5f;
        m.clearcoat = 1.0f;
        m.clearcoat_roughness = 0.3f;
    }
    const BlockedStory story(std::move(scene));
    const SampleRecord& r = story.record;
    ASSERT_EQ(r.vertices.size(), 1u);
    const VertexRecord& v = r.vertices[0];
    ASSERT_EQ(v.delta_lights.size(), 3u);
    const DeltaLightRecord& below = v.delta_lights[1];
    EXPECT_EQ(below.outcome, LightOutcome::Visible);
    EXPECT_GT(below.f_terms.transmission.x, 0.0f);
    EXPECT_EQ(below.f_terms.coat, Vec3{0.0f});
    EXPECT_EQ(below.f, below.f_terms.transmission);
    const DeltaLightRecord& side = v.delta_lights[2];
    EXPECT_GT(side.f_terms.coat.x, 0.0f);
    EXPECT_EQ(side.f_terms.transmission, Vec3{0.0f});
    const Vec3 sum = side.f_terms.diffuse + side.f_terms.lobe + side.f_terms.coat;
    EXPECT_NEAR(side.f.x, sum.x, 1e-6f * sum.x);

    const ExplainContext context{story.scene, story.job, "test.json"};
    const std::string text = explain_text(context, r);
    EXPECT_NE(text.find(" + transmission "), std::string::npos) << text;
    EXPECT_NE(text.find(" + coat "), std::string::npos) << text;
    const nlohmann::json j = nlohmann::json::parse(explain_json(context, r));
    EXPECT_TRUE(j["lights"][1]["f_r"].contains("transmission")) << j["lights"][1];
    EXPECT_FALSE(j["lights"][1]["f_r"].contains("coat")) << j["lights"][1];
    EXPECT_TRUE(j["lights"][2]["f_r"].contains("coat")) << j["lights"][2];
}

// A pbr with a sheen: the visible light from the side (ω_i grazing the
// ground) shows the sheen term, and text and JSON name it; the light below
// the ground, which the opaque base does not let through, has none.
TEST(ExplainRecord, NamesThePbrSheenTerm) {
    Scene scene = blocked_scene();
    for (Material& m : scene.materials) {
        m.type = MaterialType::Pbr;
        m.base_color = Vec3{0.6f};
        m.roughness = 0.5f;
        m.sheen_color = Vec3{1.0f, 0.5f, 0.25f};
        m.sheen_roughness = 0.6f;
    }
    const BlockedStory story(std::move(scene));
    const SampleRecord& r = story.record;
    ASSERT_EQ(r.vertices.size(), 1u);
    const VertexRecord& v = r.vertices[0];
    ASSERT_EQ(v.delta_lights.size(), 3u);
    EXPECT_EQ(v.delta_lights[1].f_terms.sheen, Vec3{0.0f});
    const DeltaLightRecord& side = v.delta_lights[2];
    EXPECT_GT(side.f_terms.sheen.x, side.f_terms.sheen.y);
    EXPECT_GT(side.f_terms.sheen.y, 0.0f);
    const Vec3 sum = side.f_terms.diffuse + side.f_terms.lobe + side.f_terms.sheen;
    EXPECT_NEAR(side.f.x, sum.x, 1e-6f * sum.x);

    const ExplainContext context{story.scene, story.job, "test.json"};
    const std::string text = explain_text(context, r);
    EXPECT_NE(text.find(" + sheen "), std::string::npos) << text;
    const nlohmann::json j = nlohmann::json::parse(explain_json(context, r));
    EXPECT_FALSE(j["lights"][1]["f_r"].contains("sheen")) << j["lights"][1];
    EXPECT_TRUE(j["lights"][2]["f_r"].contains("sheen")) << j["lights"][2];
}

// The text says where n_s came from: vertex normals even when they equal
// n_g (a flat floor's, as the shared scenes' plane.obj has), or none.
TEST(ExplainRecord, SaysWhetherTheShadingNormalCameFromVertexNormals) {
    const BlockedStory flat;
    const std::string flat_text = explain_text(ExplainContext{flat.scene, flat.job, "test.json"}, flat.record);
    EXPECT_NE(flat_text.find("(shading normal: the same, no vertex normals)"), std::string::npos) << flat_text;

    Scene scene = blocked_scene();
    TriangleMesh& mesh = scene.geometry;
    mesh.normals = {Vec3{0, 1, 0}};
    mesh.normal_indices.assign(mesh.triangles.size(), Index3{kNoNormal, kNoNormal, kNoNormal});
    mesh.normal_indices[0] = mesh.normal_indices[1] = Index3{0, 0, 0};  // the ground's
    const BlockedStory smooth(std::move(scene));
    ASSERT_EQ(smooth.record.vertices.size(), 1u);
    EXPECT_LT(smooth.record.vertices[0].surface.triangle, 2u);
    const std::string smooth_text = explain_text(ExplainContext{smooth.scene, smooth.job, "test.json"}, smooth.record);
    EXPECT_NE(smooth_text.find("(shading normal: blended vertex normals, here the same as n_g)"), std::string::npos)
        << smooth_text;
}

TEST(ExplainRecord, SvgShowsTheBlockedShadowRayInRedAndEmbedsTheImage) {
    const BlockedStory story;
    const float pixel[3] = {0.1f, 0.2f, 0.3f};
    const std::string svg =
        explain_svg(ExplainContext{story.scene, story.job, "test.json"}, story.record, ImageView{1, 1, pixel}, {});
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_NE(svg.find("blocked by blocker.obj triangle"), std::string::npos);
    EXPECT_NE(svg.find("#d0202a"), std::string::npos);                            // the blocked ray's red
    EXPECT_NE(svg.find("data:image/png;base64,iVBORw0KGgo"), std::string::npos);  // a PNG's signature, base64
}

}  // namespace
}  // namespace sombra

namespace sombra {
namespace {

// A textured material is told as the BSDF saw it: kd at the hit's uv, which
// is what f_r's diffuse term was made of, not the material's constant.
TEST(ExplainRecord, TexturedMaterialShowsItsValuesAtTheHit) {
    Diagnostics diag;
    const auto [scene, file_settings] = load_scene_file(kSource / "scenes" / "textured.json", diag);
    RenderSettings settings = file_settings;
    settings.spp = 1;
    settings.integrator = IntegratorKind::Direct;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, settings, 1);
    int textured_hits = 0;
    for (int j = settings.height / 2; j < settings.height; j += 7)
        for (int i = 0; i < settings.width; i += 11) {
            SampleRecord r;
            RayCounters counters;
            trace_pixel_sample(job, i, j, 0, counters, r);
            if (r.vertices.empty() || !r.vertices[0].hit) continue;
            const HitRecord& h = r.vertices[0].surface;
            const Material& named = scene.materials[h.material];
            if (!named.textured || !named.textures.kd.is_set() || named.type != MaterialType::Diffuse) continue;
            ++textured_hits;
            EXPECT_TRUE(h.has_uv);
            for (const DeltaLightRecord& l : r.vertices[0].delta_lights) {
                if (l.outcome == LightOutcome::Visible) {
                    EXPECT_EQ(l.f_terms.diffuse, h.shaded.kd * std::numbers::inv_pi_v<float>);
                }
            }
        }
    EXPECT_GT(textured_hits, 10) << "the textured floor should fill the lower half of the image";
}

}  // namespace
}  // namespace sombra
