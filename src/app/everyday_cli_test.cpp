// Spec §27 from the command line: the warnings a new user needs (nothing
// emits light, adaptive sampling that cannot adapt), a folder given as the
// scene, and the range of --frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

class Everyday : public CliFixture {
protected:
    static std::size_t count(const std::string& text, const std::string& what) {
        std::size_t n = 0;
        for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
        return n;
    }
};

constexpr const char* kNoLight = "nothing in the scene emits light";

TEST_F(Everyday, ASceneWithoutLightRendersBlackWithOneWarning) {
    write_text(dir_ / "dark.json", R"({"render": {"width": 16, "height": 12, "integrator": "path"},
        "camera": {"origin": [0, 0, 4], "look_at": [0, 0, 0]},
        "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}},
        "objects": [{"file": "square.obj", "material": "grey"}]})");
    const RunResult r = run("render dark.json -o dark.pfm -q");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, kNoLight), 1u) << r.err;
    EXPECT_NE(r.err.find("sombra: warning: dark.json: nothing"), std::string::npos) << r.err;
    const Pfm image = read_pfm(dir_ / "dark.pfm");
    ASSERT_EQ(image.rgb.size(), 16u * 12u * 3u);
    EXPECT_TRUE(std::all_of(image.rgb.begin(), image.rgb.end(), [](float v) { return v == 0.0f; }));

    write_text(dir_ / "lit.json", scene());
    const RunResult lit = run("render lit.json -o lit.pfm -q");
    ASSERT_EQ(lit.status, 0) << lit.err;
    EXPECT_EQ(lit.err.find(kNoLight), std::string::npos) << lit.err;
    // A white background lights the scene too.
    write_text(dir_ / "sky.json", R"({"render": {"width": 16, "height": 12}, "background": [1, 1, 1],
        "camera": {"origin": [0, 0, 4], "look_at": [0, 0, 0]}, "objects": [{"file": "square.obj"}]})");
    const RunResult sky = run("render sky.json -o sky.pfm -q");
    ASSERT_EQ(sky.status, 0) << sky.err;
    EXPECT_EQ(sky.err.find(kNoLight), std::string::npos) << sky.err;
}

TEST_F(Everyday, ANoiseThresholdThatCannotStopAnyPixelEarlyWarns) {
    write_text(dir_ / "s.json", scene(R"({"width": 16, "height": 12, "spp": 8, "integrator": "path"})"));
    const RunResult r = run("render s.json -o a.pfm -q --noise-threshold 0.1");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, "--noise-threshold cannot stop any pixel early: --min-spp 16 is not below the 8"), 1u)
        << r.err;
    const RunResult adapts = run("render s.json -o b.pfm -q --noise-threshold 0.1 --min-spp 4");
    ASSERT_EQ(adapts.status, 0) << adapts.err;
    EXPECT_EQ(adapts.err.find("cannot stop"), std::string::npos) << adapts.err;
}

TEST_F(Everyday, AFolderGivenAsTheSceneIsOneLine) {
    fs::create_directories(dir_ / "scenes.json");
    for (const char* folder : {".", "scenes.json"}) {
        const RunResult r = run(std::string("render ") + folder + " -o out.png");
        EXPECT_EQ(r.status, 1);
        EXPECT_EQ(r.err, std::string("sombra: error: ") + folder +
                             ": is a folder, not a scene: give a scene .json or a model file (.obj, .ply, .gltf, "
                             ".glb), e.g. one inside it\n");
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
}

TEST_F(Everyday, FramesRunFromZeroTo2To31Minus1) {
    write_text(dir_ / "s.json", scene());
    const RunResult last = run("render s.json -o last.png -q --frame 2147483647");
    EXPECT_EQ(last.status, 0) << last.err;
    for (const char* frame : {"2147483648", "-1"}) {
        const RunResult r = run(std::string("render s.json -o out.png -q --frame ") + frame);
        EXPECT_EQ(r.status, 2) << frame;
        EXPECT_NE(r.err.find("--frame: must be between 0 and 2147483647"), std::string::npos) << r.err;
    }
    const RunResult frames = run("render s.json -o out_#.png -q --frames 2147483647-2147483648");
    EXPECT_EQ(frames.status, 2) << frames.err;
}

}  // namespace
