// Hostile render settings, in the scene's "render" section or on the command
// line, through the real executable (docs/robustness.md, "Hostile inputs"):
// image sizes and spp out of range, a film too large for the memory, max_depth
// out of range, and the one warning the direct integrator gives for content
// only the path integrator lights.
#include <gtest/gtest.h>

#include <string>

#include "hostile_test_fixture.h"

namespace {

using namespace sombra::cli_test;

class HostileRenderSettings : public HostileFixture {};

TEST_F(HostileRenderSettings, ImageSizeZeroOrNegative) {
    for (const char* render : {R"({"width": 0, "height": 24})", R"({"width": -5, "height": 24})"}) {
        write_text(dir_ / "s.json", scene(render));
        expect_error_at(run("render s.json -o out.png"), "s.json: /render/width", "must be between 1 and 32768");
    }
    write_text(dir_ / "s.json", scene(R"({"width": 32, "height": -1})"));
    expect_error_at(run("render s.json -o out.png"), "s.json: /render/height", "must be between 1 and 32768");
    write_text(dir_ / "s.json", scene());
    expect_error_at(run("render s.json -o out.png --width 0"), "--width", "width must be between 1 and 32768");
    expect_error_at(run("render s.json -o out.png --width -4"), "--width", "width must be between 1 and 32768");
    expect_error_at(run("render s.json -o out.png --height=-4"), "--height", "height must be between 1 and 32768");
}

TEST_F(HostileRenderSettings, ImageBeyondTheSizeLimits) {
    write_text(dir_ / "s.json", scene(R"({"width": 32769, "height": 1})"));
    expect_error_at(run("render s.json -o out.png"), "s.json: /render/width", "must be between 1 and 32768");
    write_text(dir_ / "s.json", scene(R"({"width": 32768, "height": 16385})"));
    expect_error_at(run("render s.json -o out.png"), "s.json: /render",
                    "image of 32768x16385 pixels exceeds the limit of 268435456 pixels");
    write_text(dir_ / "s.json", scene());
    expect_error_at(run("render s.json -o out.png --width 40000"), "--width", "width must be between 1 and 32768");
    expect_error_at(run("render s.json -o out.png --width 32768 --height 32768"), "--height",
                    "exceeds the limit of 268435456 pixels");
    // Too large even to hold: a command-line error (exit 2), like any number the parser cannot store.
    const RunResult r = run("render s.json -o out.png --width 99999999999");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err.rfind("sombra: error: command line: ", 0), 0u) << r.err;
    // The longest side the limits allow renders.
    write_text(dir_ / "s.json", scene(R"({"width": 32768, "height": 2})"));
    ASSERT_EQ(run("render s.json -o out.pfm --quiet --threads 2").status, 0);
    EXPECT_EQ(read_pfm(dir_ / "out.pfm").width, 32768);
}

TEST_F(HostileRenderSettings, FilmTooLargeForTheMemory) {
    if (kSanitized) GTEST_SKIP() << "sanitizers reserve more address space than the limit this test sets";
    // 2^28 pixels: within the limits, but its 3 GiB of film do not fit in 1 GiB.
    write_text(dir_ / "s.json", scene(R"({"width": 16384, "height": 16384})"));
    expect_error_at(run("render s.json -o out.png --threads 2", kSmallMemoryKib), "s.json", "out of memory");
}

TEST_F(HostileRenderSettings, SppZeroNegativeOrBeyondTheLimit) {
    for (const char* spp : {"0", "-3", "65537"}) {
        write_text(dir_ / "s.json", scene(std::string(R"({"width": 32, "height": 24, "spp": )") + spp + "}"));
        expect_error_at(run("render s.json -o out.png"), "s.json: /render/spp", "must be between 1 and 65536");
        write_text(dir_ / "s.json", scene());
        expect_error_at(run(std::string("render s.json -o out.png --spp=") + spp), "--spp",
                        "spp must be between 1 and 65536");
    }
    // The limit itself is allowed.
    EXPECT_EQ(run("render s.json -o out.png --quiet --width 1 --height 1 --spp 65536").status, 0);
}

TEST_F(HostileRenderSettings, MaxDepthOutOfRangeOnTheCommandLine) {
    write_text(dir_ / "s.json", scene());
    for (const char* depth : {"2000", "-1", "2.5"}) {
        const RunResult r = run(std::string("render s.json -o out.png --quiet --max-depth ") + depth);
        EXPECT_EQ(r.status, 2) << depth << ": " << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: command line: ", 0), 0u) << r.err;
        EXPECT_EQ(count(r.err, "\n"), 1u) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
    const RunResult ok = run("render s.json -o out.png --quiet --max-depth 1024 --integrator path");
    EXPECT_EQ(ok.status, 0) << ok.err;
}

TEST_F(HostileRenderSettings, MaxVolumeDepthOutOfRangeAndMediaUnderDirect) {
    const std::string fog = R"({"render": {"width": 8, "height": 6, "spp": 1, "medium": "fog"},
        "media": {"fog": {"type": "homogeneous", "sigma_s": [1, 1, 1]}},
        "camera": {"origin": [0, 0, 3], "look_at": [0, 0, 0]},
        "lights": [{"type": "point", "position": [0, 1, 2], "intensity": [5, 5, 5]}],
        "objects": [{"file": "square.obj"}]})";
    for (const char* depth : {"65537", "-1"}) {
        const RunResult r = render(fog, std::string("--integrator path --max-volume-depth ") + depth);
        EXPECT_EQ(r.status, 2) << depth << ": " << r.err;
        EXPECT_EQ(r.err, "sombra: error: command line: --max-volume-depth: must be between 0 and 65536, not " +
                             std::string(depth) + " (see 'sombra render --help')\n");
    }
    const std::string warning = "the direct integrator ignores media (spec §26); use --integrator path";
    RunResult r = render(fog);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, warning), 1u) << r.err;
    r = render(fog, "--integrator path --max-volume-depth 0");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, warning), 0u) << r.err;
}

TEST_F(HostileRenderSettings, DirectWarnsOnceAboutContentOnlyPathLights) {
    const std::string warning = "the direct integrator lights with point, spot and directional lights only";
    const std::string quad = light_scene(
        R"({"type": "quad", "corner": [-1, 1, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "radiance": [1, 1, 1]},
                        {"type": "quad", "corner": [-1, -1, 1], "edge1": [0, 0, -2], "edge2": [2, 0, 0], "radiance": [1, 1, 1]})");
    RunResult r = render(quad);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, warning), 1u) << r.err;
    EXPECT_NE(r.err.find("sombra: warning: s.json: " + warning), std::string::npos) << r.err;

    r = render(quad, "--integrator path");  // the command line decides
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, warning), 0u) << r.err;

    r = render(material_scene(R"({"type": "dielectric"})"));
    EXPECT_EQ(count(r.err, warning), 1u) << r.err;
    const std::string path_glass =
        R"({"render": {"width": 16, "height": 12, "integrator": "path"}, "camera": )" + kCamera +
        R"(, "materials": {"m": {"type": "mirror", "kr": [1, 1, 1]}}, "objects": [{"file": "square.obj", "material": "m"}]})";
    r = render(path_glass);
    EXPECT_EQ(count(r.err, warning), 0u) << r.err;
    r = render(path_glass, "--integrator direct");
    EXPECT_EQ(count(r.err, warning), 1u) << r.err;

    // MTL illum 5 counts; version-1 emission does not.
    write_text(dir_ / "mirror.mtl", "newmtl m\nKs 1 1 1\nillum 5\n");
    write_text(dir_ / "mirror.obj", "mtllib mirror.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nusemtl m\nf 1 2 3\n");
    r = run("render mirror.obj -o out.png --quiet");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, warning), 1u) << r.err;
    r = render(material_scene(R"({"type": "diffuse", "kd": [0, 0, 0], "ke": [1, 1, 1]})"));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, warning), 0u) << r.err;
}

}  // namespace
