// Hostile inputs of the version-2 scene keys (spec §10, §11) through the real
// executable, one case per row of docs/robustness.md's version-2 table: one
// "sombra: error:" line and exit 1, no image; and the one warning that the
// direct integrator gives for content only the path integrator lights.
#include <gtest/gtest.h>

#include <vector>

#include "cli_test_fixture.h"
#include "io/images/exr_test_file.h"

namespace {

using namespace sombra::cli_test;
using sombra::testing::write_exr;

const std::string kRender = R"({"width": 16, "height": 12})";
const std::string kCamera = R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})";

class HostileV2 : public CliFixture {
protected:
    // The fixture's scene with `extra` top-level members ("," first).
    std::string scene_with(const std::string& extra, const std::string& render = kRender) {
        return scene(render, kCamera, extra);
    }
    // The fixture's square with `lights` (a JSON array) and no other light.
    std::string light_scene(const std::string& lights) {
        return R"({"render": )" + kRender + R"(, "camera": )" + kCamera +
               R"(, "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}}, "lights": )" + lights +
               R"(, "objects": [{"file": "square.obj", "material": "grey"}]})";
    }
    // A scene whose square uses material `m`.
    std::string material_scene(const std::string& material) {
        return R"({"render": )" + kRender + R"(, "camera": )" + kCamera + R"(, "materials": {"m": )" + material +
               R"(}, "objects": [{"file": "square.obj", "material": "m"}]})";
    }
    RunResult render(const std::string& scene_text, const std::string& args = "") {
        write_text(dir_ / "s.json", scene_text);
        return run("render s.json -o out.png --quiet --threads 2 " + args);
    }
    // expect_input_error, and the line names `where` first.
    void expect_error_at(const RunResult& r, const std::string& where, const std::string& what) {
        expect_input_error(r, what);
        EXPECT_EQ(r.err.rfind("sombra: error: " + where + ": ", 0), 0u) << "expected WHERE " << where << ": " << r.err;
    }
    static std::size_t count(const std::string& text, const std::string& part) {
        std::size_t n = 0;
        for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
        return n;
    }
};

TEST_F(HostileV2, BadVersionTwoValuesAreOneLineErrors) {
    const std::string quad = R"([{"type": "quad", "corner": [0, 0, 1], )";
    const struct {
        std::string text, where, what;
    } cases[] = {
        {material_scene(R"({"type": "dielectric", "ior": 1})"), "s.json: /materials/m/ior", "greater than 1"},
        {material_scene(R"({"type": "dielectric", "ior": "NaN"})"), "s.json: /materials/m/ior", "expected a number"},
        {material_scene(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": -0.1})"),
         "s.json: /materials/m/roughness", "must lie in [0, 1]"},
        {material_scene(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": 1.5})"),
         "s.json: /materials/m/roughness", "must lie in [0, 1]"},
        {material_scene(R"({"type": "mirror", "kr": [1.2, 1, 1]})"), "s.json: /materials/m/kr", "must lie in [0, 1]"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "roughness": 0.5})"),
         "s.json: /materials/m/metallic", "missing required key 'metallic'"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 1.5, "roughness": 0.5})"),
         "s.json: /materials/m/metallic", "metallic must lie in [0, 1]"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": "NaN", "roughness": 0.5})"),
         "s.json: /materials/m/metallic", "expected a number"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": -0.1})"),
         "s.json: /materials/m/roughness", "roughness must lie in [0, 1]"},
        {material_scene(R"({"type": "pbr", "base_color": [-0.1, 1, 1], "metallic": 0, "roughness": 0.5})"),
         "s.json: /materials/m/base_color", "base_color components must lie in [0, 1]"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "ior": 0.9})"),
         "s.json: /materials/m/ior", "greater than 1"},
        {material_scene(
             R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "ks": [1, 1, 1]})"),
         "s.json: /materials/m/ks", "'ks' applies only to phong and conductor materials, not pbr"},
        {scene_with("", R"({"width": 16, "height": 12, "max_depth": 1025})"), "s.json: /render/max_depth",
         "between 0 and 1024"},
        {scene_with("", R"({"width": 16, "height": 12, "max_depth": -1})"), "s.json: /render/max_depth",
         "between 0 and 1024"},
        {scene_with("", R"({"width": 16, "height": 12, "max_depth": 2.5})"), "s.json: /render/max_depth",
         "expected an integer"},
        {scene_with("", R"({"width": 16, "height": 12, "integrator": "photon"})"), "s.json: /render/integrator",
         "unknown integrator 'photon' (expected 'direct' or 'path')"},
        {light_scene(quad + R"("edge1": [1, 0, 0], "edge2": [-3, 0, 0], "radiance": [1, 1, 1]}])"), "s.json: /lights/0",
         "parallel"},
        {light_scene(quad + R"("edge1": [1, 0, 0], "edge2": [0, 0, 0], "radiance": [1, 1, 1]}])"),
         "s.json: /lights/0/edge2", "is zero"},
        {light_scene(quad + R"("edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": [-1, 1, 1]}])"),
         "s.json: /lights/0/radiance", "non-negative"},
        {scene_with(R"(, "background": [0, 0, 0], "environment": {"file": "sky.exr"})"), "s.json: /environment",
         "not both"},
        {scene_with(R"(, "environment": {"file": "missing.exr"})"), "s.json: /environment/file", "no such file"},
        {scene_with(R"(, "environment": {"file": "sky.exr", "scale": "NaN"})"), "s.json: /environment/scale",
         "expected a number"},
    };
    write_exr(dir_ / "sky.exr", 2, 1, {1, 1, 1, 1, 1, 1});
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        expect_error_at(render(c.text), c.where, c.what);
    }
}

TEST_F(HostileV2, NegativeEnvironmentPixelNeedsTheOptIn) {
    write_exr(dir_ / "ringing.exr", 2, 1, {1, 1, 1, 1, -0.25f, 1});
    const RunResult bad = render(scene_with(R"(, "environment": {"file": "ringing.exr"})"));
    expect_error_at(bad, "ringing.exr",
                    "pixel (1, 0) is negative (-0.25); add \"clamp_negative\": true to the environment to read "
                    "negative values as 0");

    const RunResult ok = render(scene_with(R"(, "environment": {"file": "ringing.exr", "clamp_negative": true})"),
                                "--integrator path --spp 1");
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_EQ(count(ok.err, "sombra: warning: "), 1u) << ok.err;
    EXPECT_NE(ok.err.find("ringing.exr: 1 negative values read as 0"), std::string::npos) << ok.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
}

TEST_F(HostileV2, MaxDepthOutOfRangeOnTheCommandLine) {
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

TEST_F(HostileV2, DirectWarnsOnceAboutContentOnlyPathLights) {
    const std::string warning = "the direct integrator lights with point, spot and directional lights only";
    const std::string quad = light_scene(
        R"([{"type": "quad", "corner": [-1, 1, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "radiance": [1, 1, 1]},
                        {"type": "quad", "corner": [-1, -1, 1], "edge1": [0, 0, -2], "edge2": [2, 0, 0], "radiance": [1, 1, 1]}])");
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
