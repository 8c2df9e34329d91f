// The command line as users meet it: the real executable, its exit status,
// its one-line messages, and the files it leaves behind.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

class Cli : public CliFixture {};

TEST_F(Cli, RendersASceneAndWritesStatistics) {
    write_text(dir_ / "s.json", scene());
    const RunResult r = run("render s.json -o out.png --stats-json stats.json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::file_size(dir_ / "out.png") > 0);
    EXPECT_NE(r.err.find("triangles"), std::string::npos);  // the summary line
    const auto stats = nlohmann::json::parse(read_text(dir_ / "stats.json"));
    for (const char* key :
         {"triangles", "width", "height", "spp", "threads", "accel", "load_seconds", "build_seconds", "render_seconds",
          "write_seconds", "total_seconds", "camera_rays", "shadow_rays", "peak_rss_bytes"})
        EXPECT_TRUE(stats.contains(key)) << key;
    EXPECT_EQ(stats["triangles"], 2);
    EXPECT_EQ(stats["width"], 32);
    EXPECT_EQ(stats["camera_rays"], 32 * 24);
    EXPECT_EQ(stats["accel"], "bvh");
    EXPECT_GT(stats["peak_rss_bytes"].get<double>(), 0);
}

TEST_F(Cli, OverridesAndQuiet) {
    write_text(dir_ / "s.json", scene());
    const RunResult r =
        run("render s.json -o out.pfm --width 8 --height 4 --spp 3 --seed 9 --threads 1 --accel brute "
            "--quiet --stats-json stats.json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "");
    const auto stats = nlohmann::json::parse(read_text(dir_ / "stats.json"));
    EXPECT_EQ(stats["width"], 8);
    EXPECT_EQ(stats["spp"], 3);
    EXPECT_EQ(stats["threads"], 1);
    EXPECT_EQ(stats["accel"], "brute");
    EXPECT_EQ(stats["camera_rays"], 8 * 4 * 3);
    EXPECT_EQ(fs::file_size(dir_ / "out.pfm"), std::string("PF\n8 4\n-1.0\n").size() + 8 * 4 * 3 * 4);
}

TEST_F(Cli, LightTreeChoices) {
    write_text(dir_ / "s.json", scene());
    for (const char* choice : {"auto", "on", "off"}) {
        const RunResult r =
            run(std::string("render s.json -o out.pfm --width 8 --height 4 --integrator path --quiet --light-tree ") +
                choice);
        EXPECT_EQ(r.status, 0) << choice << ": " << r.err;
    }
}

TEST_F(Cli, TextureFilterIsReportedAndOverridesTheScene) {
    write_text(dir_ / "s.json", scene());
    ASSERT_EQ(run("render s.json -o out.pfm --width 8 --height 4 --quiet --stats-json plain.json").status, 0);
    EXPECT_EQ(nlohmann::json::parse(read_text(dir_ / "plain.json"))["texture_filter"], "bilinear");
    const RunResult r =
        run("render s.json -o out.pfm --width 8 --height 4 --quiet --texture-filter mipmap --stats-json mip.json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(read_text(dir_ / "mip.json"));
    EXPECT_EQ(stats["texture_filter"], "mipmap");
    EXPECT_GE(stats["mipmap_seconds"].get<double>(), 0.0);
}

TEST_F(Cli, DefaultOutputIsRenderPng) {
    write_text(dir_ / "s.json", scene());
    ASSERT_EQ(run("render s.json --quiet").status, 0);
    EXPECT_TRUE(fs::exists(dir_ / "render.png"));
}

TEST_F(Cli, QuickLookOfAModel) {
    const RunResult r = run("render square.obj -o out.png --quiet --stats-json stats.json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(read_text(dir_ / "stats.json"));
    EXPECT_EQ(stats["triangles"], 2);
    EXPECT_GT(stats["shadow_rays"].get<int>(), 0);
}

TEST_F(Cli, WrongCommandLinesExitWithTwo) {
    for (const char* args :
         {"", "render", "paint s.json", "render s.json --bogus", "render s.json --spp", "render s.json --spp x",
          "render s.json --accel nope", "render s.json --threads -1", "render s.json --threads 100000",
          "render s.json --seed -1", "render s.json --exposure x", "render s.json --light-tree maybe",
          "render s.json --texture-filter trilinear", "render s.json --texture-filter"}) {
        const RunResult r = run(args);
        EXPECT_EQ(r.status, 2) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: ", 0), 0u) << args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    }
    EXPECT_EQ(run("--help").status, 0);
    EXPECT_EQ(run("--version").status, 0);
}

// The contract version sombra implements in full (spec §1–§15); the build's
// major version is the same number (CMakeLists.txt, CHANGELOG.md).
TEST_F(Cli, VersionNamesTheContractVersion) {
    const RunResult r = run("--version");
    ASSERT_EQ(r.status, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_match(r.out, m, std::regex(R"(sombra (\d+)\.\d+\.\d+ \(scene format version (\d+)\)\n)")))
        << r.out;
    EXPECT_EQ(m[2].str(), "2") << r.out;
    EXPECT_EQ(m[1].str(), m[2].str()) << r.out;
    EXPECT_EQ(r.err, "");
}

TEST_F(Cli, MissingSceneFile) { expect_input_error(run("render missing.json -o out.png"), "missing.json: "); }

TEST_F(Cli, MalformedJsonNamesLineAndColumn) {
    write_text(dir_ / "s.json", "{\n  \"render\": {\"width\": 32,}\n}\n");
    expect_input_error(run("render s.json -o out.png"), "s.json:2:");
}

TEST_F(Cli, UnknownKeyNamesItsPath) {
    write_text(dir_ / "s.json", scene(R"({"width": 32, "hieght": 24})"));
    expect_input_error(run("render s.json -o out.png"), "/render/hieght");
}

TEST_F(Cli, MissingMeshFile) {
    std::string text = scene();
    text.replace(text.find("square.obj"), 10, "nothere.obj");
    write_text(dir_ / "s.json", text);
    expect_input_error(run("render s.json -o out.png"), "nothere.obj");
}

TEST_F(Cli, CameraVectorsNotPerpendicular) {
    write_text(dir_ / "s.json",
               scene(R"({"width": 32, "height": 24})",
                     R"({"origin": [0, 0, 4], "left": [1, 0, 0], "up": [0.2, 1, 0], "forward": [0, 0, -1]})"));
    expect_input_error(run("render s.json -o out.png"), "perpendicular");
}

TEST_F(Cli, SppZeroInSceneOrOnCommandLine) {
    write_text(dir_ / "s.json", scene(R"({"width": 32, "height": 24, "spp": 0})"));
    expect_input_error(run("render s.json -o out.png"), "/render/spp");
    write_text(dir_ / "s.json", scene());
    expect_input_error(run("render s.json -o out.png --spp 0"), "--spp");
    expect_input_error(run("render s.json -o out.png --spp -4"), "--spp");
}

TEST_F(Cli, ZeroOrAbsurdImageSize) {
    write_text(dir_ / "s.json", scene(R"({"width": 0, "height": 24})"));
    expect_input_error(run("render s.json -o out.png"), "/render/width");
    write_text(dir_ / "s.json", scene(R"({"width": 1000000, "height": 1000000})"));
    expect_input_error(run("render s.json -o out.png"), "/render/");
    write_text(dir_ / "s.json", scene());
    expect_input_error(run("render s.json -o out.png --width 0"), "--width");
    expect_input_error(run("render s.json -o out.png --height 99999999"), "--height");
}

TEST_F(Cli, UnknownMaterialName) {
    std::string text = scene();
    text.replace(text.find("\"material\": \"grey\""), 18, "\"material\": \"gold\"");
    write_text(dir_ / "s.json", text);
    expect_input_error(run("render s.json -o out.png"), "gold");
}

TEST_F(Cli, UnwritableOutput) {
    write_text(dir_ / "s.json", scene());
    expect_input_error(run("render s.json -o no/such/folder/out.png"), "no/such/folder/out.png");
    expect_input_error(run("render s.json -o out.tif"), "out.tif");
    fs::create_directories(dir_ / "adir.png");
    expect_input_error(run("render s.json -o adir.png"), "adir.png");
}

TEST_F(Cli, StatisticsIntoAMissingFolderFailsBeforeRendering) {
    write_text(dir_ / "s.json", scene());
    expect_input_error(run("render s.json -o out.png --stats-json nowhere/stats.json"), "nowhere/stats.json");
}

TEST_F(Cli, FailedRunLeavesAnExistingImageUntouched) {
    write_text(dir_ / "out.png", "earlier image");
    write_text(dir_ / "s.json", "{ not json");
    const RunResult r = run("render s.json -o out.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(read_text(dir_ / "out.png"), "earlier image");
}

}  // namespace
