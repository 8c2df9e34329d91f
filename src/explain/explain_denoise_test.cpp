// What `explain --denoise` adds to the story (spec §25), from a denoised
// pixel made by hand: the JSON lists every term exactly, the text the ten
// largest and what was clamped, the SVG each pixel's weight with its sign;
// without a denoised pixel the story is spec §14's alone.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "explain/explain.h"
#include "render/test_meshes.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

// A floor under a point light, seen from above: one pixel to tell the story of.
struct FloorStory {
    Scene scene = floor_scene();
    Accel accel = make_accel(scene, AccelKind::Bvh);
    RenderJob job = make_render_job(scene, accel, RenderSettings{8, 8, 4, 0}, 1);
    SampleRecord record;
    FloorStory() {
        RayCounters counters;
        trace_pixel_sample(job, 3, 4, 0, counters, record);
    }

    static Scene floor_scene() {
        SceneBuilder b;
        TriangleMesh floor;
        testing::add_quad(floor, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, 0);
        const std::vector<Material> grey{Material{"floor", MaterialType::Diffuse, Vec3{0.5f}}};
        EXPECT_EQ(b.add_mesh(floor, grey, {}, MeshPlacement{"/objects/0", "floor.obj", std::nullopt, std::nullopt}),
                  MeshProblem::None);
        b.add_light(make_point_light({0, 3, 0}, Vec3{10.0f}));
        CameraSpec camera;
        camera.look_at = CameraLookAt{{0, 4, 0.1f}, {0, 0, 0}, {0, 1, 0}, 40};
        b.set_camera(camera);
        return b.finish();
    }
};

// Pixel (3, 4) made of twelve terms: its own halves weigh most, one
// neighbour's weight is negative, and the blue channel's sum is below 0.
DenoiseStory twelve_terms() {
    DenoiseStory story;
    story.raw = {0.25f, 0.5f, 0.125f};
    DenoisedPixel& d = story.pixel;
    const double w_own = 0.5, w_negative = -0.25;
    d.terms.push_back({3, 4, 0, {w_own, w_own, w_own}, {0.5f, 0.5f, -1.0f}});
    d.terms.push_back({3, 4, 1, {w_own, w_own, w_own}, {0.25f, 0.5f, -1.0f}});
    d.terms.push_back({4, 4, 0, {w_negative, w_negative, w_negative}, {0.1f, 0.2f, 0.3f}});
    const double w_far = 0.25 / 9.0;  // the rest of the 1, shared by nine faint terms
    for (int k = 0; k < 9; ++k)
        d.terms.push_back(
            {k % 8, k < 8 ? 0 : 7, k % 2, {w_far, w_far, w_far}, {0.001f * static_cast<float>(k + 1), 0.0f, 0.0f}});
    for (const DenoiseTerm& t : d.terms)
        for (std::size_t c = 0; c < 3; ++c) d.unclamped[c] += t.weight[c] * static_cast<double>(t.raw[c]);
    for (std::size_t c = 0; c < 3; ++c) {
        d.value[c] = std::max(static_cast<float>(d.unclamped[c]), 0.0f);
        d.clamped[c] = d.unclamped[c] < 0.0;
    }
    return story;
}

TEST(ExplainDenoise, JsonListsEveryTermToTheLastBit) {
    const FloorStory floor;
    const DenoiseStory story = twelve_terms();
    const nlohmann::json plain =
        nlohmann::json::parse(explain_json({floor.scene, floor.job, "test.json"}, floor.record));
    nlohmann::json j = nlohmann::json::parse(explain_json({floor.scene, floor.job, "test.json", &story}, floor.record));
    ASSERT_TRUE(j.contains("denoise")) << j.dump();
    const nlohmann::json d = j["denoise"];
    j.erase("denoise");
    EXPECT_EQ(j, plain) << "the rest of the story is spec §14's";
    EXPECT_FALSE(plain.contains("denoise"));

    for (std::size_t c = 0; c < 3; ++c) {
        EXPECT_EQ(d["value"][c].get<double>(), static_cast<double>(story.pixel.value[c]));
        EXPECT_EQ(d["raw"][c].get<double>(), static_cast<double>(story.raw[c]));
        EXPECT_EQ(d["clamped"][c].get<bool>(), c == 2);
    }
    ASSERT_EQ(d["weights"].size(), story.pixel.terms.size());
    for (std::size_t i = 0; i < story.pixel.terms.size(); ++i) {
        const DenoiseTerm& t = story.pixel.terms[i];
        const nlohmann::json& term = d["weights"][i];
        EXPECT_EQ(term["pixel"], nlohmann::json::array({t.x, t.y}));
        EXPECT_EQ(term["half"], t.half == 0 ? "a" : "b");
        for (std::size_t c = 0; c < 3; ++c) {
            EXPECT_EQ(term["w"][c].get<double>(), t.weight[c]) << term.dump();
            EXPECT_EQ(term["raw"][c].get<double>(), static_cast<double>(t.raw[c])) << term.dump();
        }
    }
}

TEST(ExplainDenoise, TextAddsTheTenLargestTermsAndWhatWasClamped) {
    const FloorStory floor;
    const DenoiseStory story = twelve_terms();
    const std::string plain = explain_text({floor.scene, floor.job, "test.json"}, floor.record);
    const std::string text = explain_text({floor.scene, floor.job, "test.json", &story}, floor.record);
    ASSERT_EQ(text.rfind(plain, 0), 0u) << "spec §14's story first, unchanged";
    const std::string added = text.substr(plain.size());
    EXPECT_EQ(added.rfind("\nDenoised pixel (3, 4)", 0), 0u) << added;
    EXPECT_NE(added.find("12 terms with a nonzero weight"), std::string::npos) << added;
    EXPECT_NE(added.find("of one of 11 pixels"), std::string::npos) << added;
    EXPECT_NE(added.find("in columns 0 to 7 and rows 0 to 7"), std::string::npos) << added;
    EXPECT_NE(added.find("add up to (1, 1, 1)"), std::string::npos) << added;
    EXPECT_NE(added.find("(clamped to 0: B)"), std::string::npos) << added;
    EXPECT_NE(added.find("the 10 largest"), std::string::npos) << added;
    // The two smallest (pixels (0, 0) and (1, 0), |w·c| below 0.0001) are left out.
    EXPECT_EQ(added.find("    (0, 0)  "), std::string::npos) << added;
    EXPECT_EQ(added.find("    (1, 0)  "), std::string::npos) << added;
    EXPECT_NE(added.find("    (4, 4)  "), std::string::npos) << added;
    // The own halves add the most (|w·c| 1 and 0.875): first, in that order.
    EXPECT_LT(added.find("    (3, 4)  A"), added.find("    (3, 4)  B")) << added;
    EXPECT_LT(added.find("    (3, 4)  B"), added.find("    (4, 4)")) << added;
}

TEST(ExplainDenoise, SvgMapsEachPixelsWeightWithItsSign) {
    const FloorStory floor;
    const DenoiseStory story = twelve_terms();
    const float pixels[8 * 8 * 3] = {};
    const ImageView image{8, 8, pixels};
    const std::string plain = explain_svg({floor.scene, floor.job, "test.json"}, floor.record, image, {});
    const std::string svg = explain_svg({floor.scene, floor.job, "test.json", &story}, floor.record, image, {});
    EXPECT_EQ(plain.find("denoise"), std::string::npos);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_NE(svg.find("<g id=\"denoise-weights\">"), std::string::npos);
    // Both halves of (3, 4) together weigh 1, the most: the full red; (4, 4)'s
    // −0.25 is blue at √(1/4) = half strength.
    EXPECT_NE(svg.find("fill=\"#b2182b\"><title>(3, 4): w = 1</title>"), std::string::npos) << svg;
    EXPECT_NE(svg.find("fill=\"#90b3d6\"><title>(4, 4): w = -0.25</title>"), std::string::npos) << svg;
    EXPECT_NE(svg.find("4 spp, before denoising"), std::string::npos);
}

}  // namespace
}  // namespace sombra
