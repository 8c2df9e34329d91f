// `sombra explain` through the real executable (spec §14): the value its JSON
// reports is the pixel `sombra render` writes, to the last bit; wrong pixels,
// samples and files are one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

const std::string kSource = SOMBRA_SOURCE_DIR;

class ExplainCli : public CliFixture {
protected:
    // The repository's path-traced Cornell box: quad light, MIS, Russian roulette.
    std::string cornell() const { return shell_quote(kSource + "/scenes/cornell-box-path.json"); }

    // The value explain reports for pixel (x, y) with `args`, as the floats it printed.
    std::vector<float> explained(int x, int y, const std::string& args) {
        const RunResult r =
            run("explain " + cornell() + " " + std::to_string(x) + " " + std::to_string(y) + " --json " + args);
        EXPECT_EQ(r.status, 0) << r.err;
        const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
        if (j.is_discarded() || !j.contains("value")) {
            ADD_FAILURE() << "not a JSON object with a value: " << r.out;
            return {};
        }
        EXPECT_EQ(j["pixel"], nlohmann::json::array({x, y}));
        return {static_cast<float>(j["value"][0].get<double>()), static_cast<float>(j["value"][1].get<double>()),
                static_cast<float>(j["value"][2].get<double>())};
    }
};

TEST_F(ExplainCli, JsonValueIsTheRenderedPixelBitForBit) {
    for (const std::string integrator : {"direct", "path"}) {
        const std::string args = "--width 24 --height 24 --spp 1 --integrator " + integrator + " --quiet";
        ASSERT_EQ(run("render " + cornell() + " -o out.pfm " + args).status, 0);
        const Pfm image = read_pfm(dir_ / "out.pfm");
        ASSERT_EQ(image.width, 24);
        for (const auto& [x, y] :
             {std::pair{12, 12}, std::pair{3, 20}, std::pair{20, 4}, std::pair{12, 1}, std::pair{0, 23}}) {
            const std::vector<float> value = explained(x, y, args);
            ASSERT_EQ(value.size(), 3u);
            const float* pixel = &image.rgb[(static_cast<std::size_t>(23 - y) * 24 + static_cast<std::size_t>(x)) * 3];
            EXPECT_EQ(std::memcmp(value.data(), pixel, 3 * sizeof(float)), 0)
                << integrator << " pixel (" << x << ", " << y << "): explain " << value[0] << " " << value[1] << " "
                << value[2] << ", render " << pixel[0] << " " << pixel[1] << " " << pixel[2];
        }
    }
}

TEST_F(ExplainCli, MipmappedTexturesAreTheRenderedPixelBitForBit) {
    // The repository's textured scene (checker floor to the horizon, sign,
    // normal-mapped tiles, roughness-mapped metal) with mip-mapping on: explain
    // re-traces the sample with the same ray cones, so the same levels.
    const std::string scene = shell_quote(kSource + "/scenes/textured.json");
    const std::string args = "--width 48 --height 32 --spp 1 --max-depth 3 --texture-filter mipmap --quiet";
    ASSERT_EQ(run("render " + scene + " -o out.pfm " + args).status, 0);
    const Pfm image = read_pfm(dir_ / "out.pfm");
    ASSERT_EQ(image.width, 48);
    int footprints = 0;
    for (const auto& [x, y] : {std::pair{24, 28}, std::pair{24, 14}, std::pair{5, 12}, std::pair{20, 12},
                               std::pair{40, 15}, std::pair{30, 18}, std::pair{2, 30}}) {
        const RunResult r =
            run("explain " + scene + " " + std::to_string(x) + " " + std::to_string(y) + " --json " + args);
        ASSERT_EQ(r.status, 0) << r.err;
        const nlohmann::json j = nlohmann::json::parse(r.out);
        const float value[3] = {static_cast<float>(j["value"][0].get<double>()),
                                static_cast<float>(j["value"][1].get<double>()),
                                static_cast<float>(j["value"][2].get<double>())};
        const float* pixel = &image.rgb[(static_cast<std::size_t>(31 - y) * 48 + static_cast<std::size_t>(x)) * 3];
        EXPECT_EQ(std::memcmp(value, pixel, sizeof value), 0) << "pixel (" << x << ", " << y << ")";
        footprints += r.out.find("\"uv_footprint\"") != std::string::npos;
    }
    EXPECT_GT(footprints, 0) << "some of these pixels see a texture through a footprint";
}

TEST_F(ExplainCli, TextTellsTheStoryAndSvgDrawsIt) {
    const RunResult r =
        run("explain " + cornell() + " 12 20 --width 24 --height 24 --spp 2 --sample 1 --svg story.svg --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("Pixel (12, 20), sample 1 of 2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Camera ray"), std::string::npos);
    EXPECT_NE(r.out.find("Vertex 0"), std::string::npos);
    EXPECT_NE(r.out.find("Value of this sample"), std::string::npos);
    const std::string svg = read_text(dir_ / "story.svg");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    expect_no_temp_files();
}

TEST_F(ExplainCli, APathThroughMediaIsToldAndIsTheRenderedPixel) {
    // Fog outside, a box of smoke behind interface surfaces, a point light:
    // the story names the interfaces crossed, the media gone through and the
    // scattering events, and its value is the rendered pixel to the last bit.
    write_text(dir_ / "box.obj",
               "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n"
               "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n"
               "f 3 7 4\nf 4 7 8\n");
    write_text(dir_ / "smoke.json", R"({
        "render": {"integrator": "path", "width": 16, "height": 16, "spp": 4},
        "media": {"fog": {"type": "homogeneous", "sigma_s": [0.05, 0.05, 0.05]},
                  "smoke": {"type": "homogeneous", "sigma_a": [0.2, 0.2, 0.2], "sigma_s": [2, 2, 2], "g": 0.4}},
        "camera": {"origin": [0, 0, 6], "look_at": [0, 0, 0], "fov": 30, "medium": "fog"},
        "lights": [{"type": "point", "position": [0, 4, 2], "intensity": [30, 30, 30]}],
        "objects": [{"file": "box.obj", "material": "interface", "interior": "smoke"}]
    })");
    const std::string args = " --quiet";
    ASSERT_EQ(run("render smoke.json -o out.pfm" + args).status, 0);
    const Pfm image = read_pfm(dir_ / "out.pfm");
    ASSERT_EQ(image.width, 16);
    const RunResult text = run("explain smoke.json 8 8 --sample 0 --svg story.svg" + args);
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_NE(text.out.find("through  medium \"fog\""), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("crosses  the interface"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("into medium \"smoke\""), std::string::npos) << text.out;
    EXPECT_NE(read_text(dir_ / "story.svg").find("</svg>"), std::string::npos);
    bool scattered = false;
    for (int sample = 0; sample < 4; ++sample) {
        const RunResult r = run("explain smoke.json 8 8 --json --sample " + std::to_string(sample) + args);
        ASSERT_EQ(r.status, 0) << r.err;
        const nlohmann::json j = nlohmann::json::parse(r.out);
        EXPECT_EQ(j["vertices"][0]["media"]["segments"][0]["medium"].get<std::string>(), "fog");
        for (const nlohmann::json& v : j["vertices"])
            if (v.contains("scatter")) {
                const std::string medium = v["scatter"]["medium"].get<std::string>();
                scattered = scattered || medium == "smoke";
                EXPECT_TRUE(medium == "smoke" || medium == "fog") << medium;
                EXPECT_TRUE(v["lights"][0].contains("phase")) << v.dump();
                EXPECT_TRUE(v["lights"][0].contains("transmittance")) << v.dump();
            }
    }
    EXPECT_TRUE(scattered) << "a sample through 2 units of smoke of σ_s 2 scatters in it";
    // Every sample's value sums to the pixel the render wrote.
    float sum[3] = {0, 0, 0};
    for (int sample = 0; sample < 4; ++sample) {
        const nlohmann::json j =
            nlohmann::json::parse(run("explain smoke.json 8 8 --json --sample " + std::to_string(sample) + args).out);
        for (int c = 0; c < 3; ++c) sum[c] += static_cast<float>(j["value"][c].get<double>());
    }
    const float* pixel = &image.rgb[(static_cast<std::size_t>(15 - 8) * 16 + 8) * 3];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / 4.0f, pixel[c], 1e-6f * std::max(1.0f, pixel[c]));
    expect_no_temp_files();
}

TEST_F(ExplainCli, PixelOrSampleOutsideTheImageIsAnInputError) {
    write_text(dir_ / "s.json", scene());  // 32×24, 1 spp
    expect_input_error(run("explain s.json 32 0"), "pixel (32, 0): outside the 32x24 image");
    expect_input_error(run("explain s.json 0 -1"), "pixel (0, -1): outside");
    expect_input_error(run("explain s.json 5 5 --sample 1"),
                       "--sample: sample 1 does not exist: the pixel has 1 sample");
    expect_input_error(run("explain s.json 5 5 --spp 4 --sample 4"), "the pixel has 4 samples (0 to 3)");
    // The pixel is checked against the size after the overrides.
    expect_input_error(run("explain s.json 20 5 --width 16"), "outside the 16x24 image");
}

TEST_F(ExplainCli, BadFilesAreInputErrorsAndWriteNothing) {
    write_text(dir_ / "s.json", scene());
    expect_input_error(run("explain missing.json 1 1"), "missing.json");
    write_text(dir_ / "broken.json", "{\"render\": ");
    expect_input_error(run("explain broken.json 1 1"), "broken.json");
    expect_input_error(run("explain s.json 1 1 --svg nowhere/story.svg"), "folder 'nowhere' does not exist");
    expect_input_error(run("explain s.json 1 1 --svg story.png"), "must end in .svg");
}

TEST_F(ExplainCli, MalformedCommandLinesExitTwo) {
    write_text(dir_ / "s.json", scene());
    for (const std::string args : {"explain s.json", "explain s.json 1", "explain s.json x 2", "explain s.json 1 2.5",
                                   "explain s.json 1 2 --bogus", "explain s.json 1 2 --sample"}) {
        const RunResult r = run(args);
        EXPECT_EQ(r.status, 2) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: command line: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find("(see 'sombra explain --help')"), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

}  // namespace
