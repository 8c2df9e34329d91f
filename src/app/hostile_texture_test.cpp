// Hostile textures (spec §12) through the real executable, one case per row
// of docs/robustness.md's texture table: a scene file's bad texture is one
// "sombra: error:" line and exit 1 with no image; an MTL file's is a warning
// and the constant is used.
#include <gtest/gtest.h>

#include <vector>

#include "hostile_test_fixture.h"
#include "io/images/image_test_files.h"

namespace {

using namespace sombra::cli_test;

const std::string kHead =
    R"({"render": {"width": 16, "height": 12}, "camera": {"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40},
  "lights": [{"position": [0, 0, 3], "intensity": [5, 5, 5]}], )";

class HostileTextures : public HostileFixture {
protected:
    void SetUp() override {
        HostileFixture::SetUp();
        write_text(dir_ / "uv.obj",
                   "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
        sombra::testing::write_png_file(dir_ / "good.png", 2, 2, 3, 8,
                                        {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255});
        std::vector<std::uint16_t> noise;
        for (int i = 0; i < 32 * 32 * 3; ++i) noise.push_back(static_cast<std::uint16_t>((i * 7919) % 65521));
        sombra::testing::write_png_file(dir_ / "deep.png", 32, 32, 3, 16, noise);
    }
    // A scene whose square (with uvs) has material `m`.
    std::string textured_scene(const std::string& material) {
        return kHead + R"("materials": {"m": )" + material + R"(}, "objects": [{"file": "uv.obj", "material": "m"}]})";
    }
    std::string bytes_of(const char* name) {
        const std::vector<unsigned char> b = sombra::testing::read_file_bytes(dir_ / name);
        return {b.begin(), b.end()};
    }
};

TEST_F(HostileTextures, BadSceneTexturesAreOneLineErrors) {
    const std::string deep = bytes_of("deep.png");
    write_text(dir_ / "half.png", deep.substr(0, deep.size() / 2));
    write_text(dir_ / "huge.png", sombra::testing::png_claiming(16000, 16000));
    write_text(dir_ / "wide.png", sombra::testing::png_claiming(100000, 1));
    write_text(dir_ / "text.png", "not an image at all\n");
    const char gif[] = "GIF89a\x02\x00\x02\x00";  // a 2x2 GIF's first bytes, NULs included
    write_text(dir_ / "anim.gif", std::string(gif, sizeof gif - 1));
    write_text(dir_ / "empty.png", "");
    fs::create_directories(dir_ / "folder.png");
    const struct {
        std::string material, where, what;
    } cases[] = {
        {R"({"type": "diffuse", "kd": {"texture": "missing.png"}})", "s.json: /materials/m/kd/texture",
         "cannot open texture 'missing.png': no such file"},
        {R"({"type": "diffuse", "kd": {"texture": "folder.png"}})", "s.json: /materials/m/kd/texture",
         "'folder.png' is not a regular file"},
        {R"({"type": "diffuse", "kd": {"texture": "half.png"}})", "half.png",
         "PNG file is truncated: an IDAT chunk claims "},
        {R"({"type": "diffuse", "kd": {"texture": "huge.png"}})", "huge.png",
         "image is 16000×16000 pixels of 4 channels, more than the limit"},
        {R"({"type": "diffuse", "kd": {"texture": "wide.png"}})", "wide.png", "more than the limit"},
        {R"({"type": "diffuse", "kd": {"texture": "text.png"}})", "text.png", "cannot read the TGA header"},
        {R"({"type": "diffuse", "kd": {"texture": "anim.gif"}})", "anim.gif", "unsupported image format: a GIF image"},
        {R"({"type": "diffuse", "kd": {"texture": "empty.png"}})", "empty.png", "image file is empty"},
        {R"({"type": "diffuse", "kd": {"texture": "good.png", "scale": [1.5, 1, 1]}})", "s.json: /materials/m/kd/scale",
         "kd components must lie in [0, 1]"},
        {R"({"type": "diffuse", "kd": {"texture": "good.png", "wrap": "clamp"}})", "s.json: /materials/m/kd/wrap",
         "unknown key 'wrap'"},
        {R"({"type": "conductor", "ks": [1, 1, 1], "roughness": {"texture": "good.png", "channel": "alpha"}})",
         "s.json: /materials/m/roughness/channel", "unknown channel 'alpha'"},
        {R"({"type": "diffuse", "kd": [1, 1, 1], "normal_map": ""})", "s.json: /materials/m/normal_map",
         "expected an image file name"},
        {R"({"type": "diffuse", "kd": [1, 1, 1], "alpha": {"texture": "good.png", "cutoff": -1}})",
         "s.json: /materials/m/alpha/cutoff", "cutoff must lie in [0, 1]"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.material);
        const RunResult r = render(textured_scene(c.material));
        expect_error_at(r, c.where, c.what);
        EXPECT_LT(r.seconds, 10.0);
    }
}

TEST_F(HostileTextures, BadMtlTexturesWarnAndRenderTheConstant) {
    const std::string deep = bytes_of("deep.png");
    write_text(dir_ / "half.png", deep.substr(0, deep.size() / 2));
    write_text(dir_ / "huge.png", sombra::testing::png_claiming(16000, 16000));
    write_text(dir_ / "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nmap_Kd missing.png\nnorm half.png\nmap_Ke huge.png\n");
    write_text(dir_ / "mtl.obj",
               "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
               "usemtl a\nf 1/1 2/2 3/3 4/4\n");
    const RunResult r = run("render mtl.obj -o out.png --quiet");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
    for (const char* what : {"texture 'missing.png': no such file", "texture 'half.png': PNG file is truncated",
                             "texture 'huge.png': image is 16000×16000 pixels"}) {
        EXPECT_NE(r.err.find(what), std::string::npos) << what << " in: " << r.err;
    }
    // Each warning one line, and the same image as the MTL without the maps.
    const std::string with_maps = bytes_of("out.png");
    write_text(dir_ / "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\n");
    const RunResult plain = run("render mtl.obj -o out.png --quiet");
    EXPECT_EQ(plain.status, 0) << plain.err;
    EXPECT_EQ(bytes_of("out.png"), with_maps);
}

TEST_F(HostileTextures, GoodTexturesAndCutOutsRenderQuietly) {
    RunResult r = render(textured_scene(
        R"({"type": "phong", "kd": {"texture": "good.png"}, "ks": {"texture": "deep.png", "scale": [0.2, 0.2, 0.2]},
                             "shininess": 10, "normal_map": "deep.png"})"));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    r = render(textured_scene(R"({"type": "diffuse", "kd": [1, 1, 1], "alpha": {"texture": "good.png"}})"),
               "--integrator path --spp 1");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
}

}  // namespace
