// The library API's options (api/render_options.h) and steps (api/session.h):
// every front end gets the same checks and messages from here, so these pin
// the ranges, the names and what a job is built from.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "api/render_options.h"
#include "api/session.h"
#include "io/scene_json/scene_file.h"

namespace sombra {
namespace {

// The message of what `f` throws, as "WHERE: WHAT"; "" when it throws nothing.
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.where() + ": " + e.message();
    }
    return {};
}

TEST(RenderOptions, DefaultsPass) {
    EXPECT_EQ(error_of([] { check_render_options(RenderOptions{}); }), "");
}

TEST(RenderOptions, EachRangeIsCheckedAtBothEnds) {
    const auto with = [](auto set) {
        RenderOptions o;
        set(o);
        return error_of([&o] { check_render_options(o); });
    };
    EXPECT_EQ(with([](RenderOptions& o) { o.threads = kMaxThreads; }), "");
    EXPECT_EQ(with([](RenderOptions& o) { o.threads = kMaxThreads + 1; }),
              "--threads: must be between 0 and 4096, not 4097");
    EXPECT_EQ(with([](RenderOptions& o) { o.threads = -1; }), "--threads: must be between 0 and 4096, not -1");
    EXPECT_EQ(with([](RenderOptions& o) { o.frame = kMaxFrame; }), "");
    EXPECT_EQ(with([](RenderOptions& o) { o.frame = kMaxFrame + 1; }),
              "--frame: must be between 0 and 2147483647, not 2147483648");
    EXPECT_EQ(with([](RenderOptions& o) { o.frame = -1; }), "--frame: must be between 0 and 2147483647, not -1");
    EXPECT_EQ(with([](RenderOptions& o) { o.overrides.max_depth = kMaxDepth + 1; }),
              "--max-depth: must be between 0 and 1024, not 1025");
    EXPECT_EQ(with([](RenderOptions& o) { o.overrides.max_depth = 0; }), "");
    EXPECT_EQ(with([](RenderOptions& o) { o.min_spp = 0; }), "--min-spp: must be between 1 and 65536, not 0");
    EXPECT_EQ(with([](RenderOptions& o) { o.min_spp = kMaxSpp; }), "");
    EXPECT_EQ(with([](RenderOptions& o) { o.time_budget = kMaxTimeBudget; }), "");
    EXPECT_EQ(with([](RenderOptions& o) { o.time_budget = 0.0; }),
              "--time: must be a number above 0 and at most 10000000, not 0");
    EXPECT_EQ(with([](RenderOptions& o) { o.time_budget = std::numeric_limits<double>::infinity(); }),
              "--time: must be a number above 0 and at most 10000000, not inf");
    EXPECT_EQ(with([](RenderOptions& o) { o.noise_threshold = std::nan(""); }),
              "--noise-threshold: must be a number above 0 and at most 1000000, not nan");
}

TEST(RenderOptions, OverridesReplaceTheScenesSettingsAndNameTheOption) {
    RenderSettings scene;
    scene.width = 100;
    scene.spp = 4;
    SettingOverrides o;
    o.height = 30;
    o.integrator = IntegratorKind::Path;
    o.texture_filter = TextureFilter::Mipmap;
    o.seed = 7;
    const RenderSettings s = resolve_settings(scene, o);
    EXPECT_EQ(s.width, 100);
    EXPECT_EQ(s.height, 30);
    EXPECT_EQ(s.spp, 4);
    EXPECT_EQ(s.seed, 7u);
    EXPECT_EQ(s.integrator, IntegratorKind::Path);
    EXPECT_EQ(s.texture_filter, TextureFilter::Mipmap);

    o.spp = 0;
    EXPECT_EQ(error_of([&] { resolve_settings(scene, o); }), "--spp: spp must be between 1 and 65536");
    o.spp.reset();
    o.width = 40000;
    EXPECT_EQ(error_of([&] { resolve_settings(scene, o); }), "--width: width must be between 1 and 32768");
}

TEST(RenderOptions, ATimeBudgetWithoutSppLetsTheBudgetDecide) {
    RenderSettings scene;
    scene.spp = 4;
    RenderOptions o;
    o.time_budget = 2.0;
    EXPECT_EQ(resolve_render_settings(scene, o).spp, kMaxSpp);
    o.overrides.spp = 8;
    EXPECT_EQ(resolve_render_settings(scene, o).spp, 8);
    o.time_budget.reset();
    EXPECT_EQ(resolve_render_settings(scene, o).spp, 8);
}

TEST(RenderOptions, NamesReadBackAndUnknownNamesAreOneMessage) {
    for (IntegratorKind k : {IntegratorKind::Direct, IntegratorKind::Path})
        EXPECT_EQ(integrator_option(integrator_name(k)), k);
    for (TextureFilter f : {TextureFilter::Bilinear, TextureFilter::Mipmap})
        EXPECT_EQ(texture_filter_option(texture_filter_name(f)), f);
    for (LightSelection l : {LightSelection::Automatic, LightSelection::Tree, LightSelection::Power})
        EXPECT_EQ(light_selection_option(light_selection_name(l)), l);
    for (std::string_view name : available_accels()) EXPECT_EQ(accel_name(accel_option(name)), name);
    EXPECT_EQ(error_of([] { integrator_option("bdpt"); }),
              "--integrator: unknown integrator 'bdpt' (expected direct or path)");
    EXPECT_EQ(error_of([] { texture_filter_option("Mipmap"); }),
              "--texture-filter: unknown texture filter 'Mipmap' (expected bilinear or mipmap)");
    EXPECT_EQ(error_of([] { light_selection_option(""); }),
              "--light-tree: unknown light choice '' (expected auto, on or off)");
    EXPECT_NE(error_of([] { accel_option("kd"); }).find("--accel: unknown accelerator 'kd' (available: bvh"),
              std::string::npos);
}

TEST(RenderOptions, AovListsReadBackInSpecOrder) {
    const AovSet set = aov_option("spp,albedo,depth,albedo");
    EXPECT_TRUE(set.albedo && set.depth && set.spp && !set.normal && !set.position);
    EXPECT_EQ(aov_list(set), "albedo,depth,spp");
    EXPECT_EQ(aov_list(AovSet{}), "");
    EXPECT_EQ(error_of([] { aov_option("albedo,,depth"); }),
              "--aov: unknown AOV '' (expected a comma-separated list of albedo, normal, depth, position, spp, "
              "variance, noisy, denoise)");
}

TEST(Session, TheJobCarriesTheOptions) {
    Diagnostics diag;
    LoadedScene loaded =
        load_scene_file(std::filesystem::path(SOMBRA_SOURCE_DIR) / "scenes" / "cornell-box.json", diag);
    RenderOptions o;
    o.threads = 3;
    o.light_selection = LightSelection::Tree;
    o.noise_threshold = 0.05;
    o.min_spp = 8;
    o.time_budget = 10.0;
    o.aovs.depth = true;
    o.overrides.width = 32;
    o.overrides.height = 24;
    const RenderSettings settings = resolve_render_settings(loaded.settings, o);
    prepare_scene(loaded.scene, settings, o, "cornell-box.json");
    const Accel accel = make_accel(loaded.scene, o.accel);
    const auto start = std::chrono::steady_clock::now();
    const RenderJob job = make_job(loaded.scene, accel, settings, o, start);
    EXPECT_EQ(job.threads, 3);
    EXPECT_EQ(job.settings.width, 32);
    EXPECT_EQ(job.limits.noise_threshold, 0.05);
    EXPECT_EQ(job.limits.min_spp, 8);
    ASSERT_TRUE(job.limits.deadline.has_value());
    EXPECT_EQ(*job.limits.deadline - start,
              std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(10.0)));
    EXPECT_TRUE(job.aovs.depth);
    EXPECT_FALSE(job.aovs.albedo);

    // explain's sample is the render's: the recorded value equals the traced one.
    RenderSettings one = settings;
    one.spp = 2;
    const RenderJob small = make_job(loaded.scene, accel, one, RenderOptions{}, start);
    const SampleRecord record = record_pixel_sample(small, 16, 12, 1);
    RayCounters counters;
    SampleRecord again;
    const Vec3 traced = trace_pixel_sample(small, 16, 12, 1, counters, again);
    EXPECT_EQ(record.value.x, traced.x);
    EXPECT_EQ(record.value.y, traced.y);
    EXPECT_EQ(record.value.z, traced.z);
}

TEST(Session, ExplainTellsAPathThroughAMedium) {
    Diagnostics diag;
    LoadedScene loaded =
        load_scene_file(std::filesystem::path(SOMBRA_SOURCE_DIR) / "scenes" / "cornell-box-path.json", diag);
    Medium fog;
    fog.name = "fog";
    fog.sigma_s = Vec3{1.0f};
    loaded.scene.media = {fog};
    loaded.scene.render_medium = 0;
    RenderOptions o;
    o.overrides.width = 8;
    o.overrides.height = 8;
    o.overrides.spp = 8;
    const RenderSettings settings = resolve_render_settings(loaded.settings, o);
    const Accel accel = make_accel(loaded.scene, o.accel);
    const RenderJob job = make_job(loaded.scene, accel, settings, o, std::chrono::steady_clock::now());
    // Every sample's story starts with the fog the camera ray crossed, and
    // its value is the traced one, bit for bit; some scatter in it.
    int medium_events = 0;
    for (int sample = 0; sample < 8; ++sample) {
        const SampleRecord record = record_pixel_sample(job, 4, 4, sample);
        ASSERT_FALSE(record.vertices.empty());
        ASSERT_EQ(record.vertices[0].segments.size(), 1u);
        EXPECT_EQ(record.vertices[0].segments[0].medium, 0u);
        for (const VertexRecord& v : record.vertices) medium_events += v.medium_event ? 1 : 0;
        RayCounters counters;
        SampleRecord again;
        const Vec3 traced = trace_pixel_sample(job, 4, 4, sample, counters, again);
        EXPECT_EQ(record.value.x, traced.x);
        EXPECT_EQ(record.value.y, traced.y);
        EXPECT_EQ(record.value.z, traced.z);
    }
    EXPECT_GT(medium_events, 0);
}

TEST(Session, ExplainPixelIsCheckedAgainstTheImage) {
    RenderSettings s;
    s.width = 48;
    s.height = 36;
    s.spp = 4;
    EXPECT_EQ(error_of([&] { check_explain_pixel(47, 35, 3, s); }), "");
    EXPECT_EQ(error_of([&] { check_explain_pixel(48, 0, 0, s); }),
              "pixel (48, 0): outside the 48x36 image (columns 0 to 47, rows 0 to 35)");
    EXPECT_EQ(error_of([&] { check_explain_pixel(0, -1, 0, s); }),
              "pixel (0, -1): outside the 48x36 image (columns 0 to 47, rows 0 to 35)");
    EXPECT_EQ(error_of([&] { check_explain_pixel(0, 0, 4, s); }),
              "--sample: sample 4 does not exist: the pixel has 4 samples (0 to 3)");
}

}  // namespace
}  // namespace sombra
