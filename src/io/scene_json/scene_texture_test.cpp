// Textures in scene files and MTL files (spec §12): which parameter gets
// which image, scales and channels, sharing one decoded image, renumbering
// when meshes join the scene, and the errors (scene file) or warnings (MTL)
// for missing images.
#include <gtest/gtest.h>

#include <string>

#include "io/images/image_test_files.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"

namespace sombra {
namespace {

using testing::TempFolder;

const std::string kHead = R"({"camera": {"origin": [0, 0, 4], "look_at": [0, 0, 0]}, )";

class SceneTextures : public ::testing::Test {
protected:
    void SetUp() override {
        // 2×1 RGB: left texel code 255/0/0, right 0/0/255 (8 bit); and a grey 16-bit 1×1.
        testing::write_png_file(tmp.path / "rb.png", 2, 1, 3, 8, {255, 0, 0, 0, 0, 255});
        testing::write_png_file(tmp.path / "g16.png", 1, 1, 4, 16, {0, 32768, 65535, 16384});
        tmp.write("quad.obj",
                  "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                  "usemtl painted\nf 1/1 2/2 3/3 4/4\n");
    }
    Scene load(const std::string& materials,
               const std::string& objects = R"([{"file": "quad.obj", "material": "m"}])") {
        return load_scene_text(kHead + R"("materials": )" + materials + R"(, "objects": )" + objects + "}",
                               tmp.path / "scene.json", diag)
            .scene;
    }
    std::string error_of(const std::string& materials) {
        try {
            load(materials);
        } catch (const Error& e) {
            return e.what();
        }
        return "loaded";
    }
    TempFolder tmp;
    Diagnostics diag;
};

TEST_F(SceneTextures, ColourParametersTakeATextureAndAScale) {
    const Scene s = load(R"({"m": {"type": "phong", "kd": {"texture": "rb.png", "scale": [0.5, 1, 0.25]},
                                   "ks": {"texture": "rb.png"}, "shininess": 10, "ke": {"texture": "g16.png"}}})");
    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    EXPECT_TRUE(m.textured);
    EXPECT_EQ(m.kd, (Vec3{0.5f, 1, 0.25f}));
    EXPECT_EQ(m.ks, Vec3{1.0f});  // no scale: 1
    EXPECT_EQ(m.ke, Vec3{1.0f});
    ASSERT_EQ(s.textures.size(), 2u);  // rb.png decoded once for kd and ks
    EXPECT_EQ(m.textures.kd.texture, m.textures.ks.texture);
    const Texture& rb = s.textures[m.textures.kd.texture];
    EXPECT_EQ(rb.encoding, TextureEncoding::Color);
    EXPECT_EQ(rb.texels, (std::vector<float>{1, 0, 0, 0, 0, 1}));
    EXPECT_EQ(s.textures[m.textures.ke.texture].channels, 4);
    EXPECT_FALSE(m.textures.normal_map.is_set());
}

TEST_F(SceneTextures, ScalarsNormalMapsAndAlpha) {
    const Scene s = load(R"({"m": {"type": "conductor", "ks": [1, 1, 1],
                                   "roughness": {"texture": "g16.png", "channel": "g", "scale": 0.5},
                                   "normal_map": "g16.png", "alpha": {"texture": "g16.png", "cutoff": 0.25}}})");
    const Material& m = s.materials[0];
    EXPECT_EQ(m.roughness, 0.5f);
    EXPECT_EQ(m.textures.roughness.channel, 1);
    EXPECT_EQ(m.textures.alpha.channel, 3);  // RGBA: A
    EXPECT_EQ(m.textures.alpha_cutoff, 0.25f);
    // One data decoding of g16.png serves all three, values as stored.
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].encoding, TextureEncoding::Data);
    EXPECT_EQ(s.textures[0].texels[1], 32768.0f / 65535.0f);
    // An alpha texture turns the test on, with the factor left at 1, quietly.
    EXPECT_TRUE(m.textures.alpha_test);
    EXPECT_EQ(m.textures.alpha_factor, 1.0f);
    for (const std::string& w : diag.warnings) EXPECT_EQ(w.find("alpha"), std::string::npos) << w;
}

TEST_F(SceneTextures, PbrTakesBaseColourAndGltfStyleMetallicRoughness) {
    const Scene s = load(R"({"m": {"type": "pbr", "base_color": {"texture": "rb.png", "scale": [1, 0.5, 1]},
                                   "roughness": {"texture": "g16.png", "channel": "g"},
                                   "metallic": {"texture": "g16.png", "channel": "b", "scale": 0.75}}})");
    const Material& m = s.materials[0];
    EXPECT_TRUE(m.textured);
    EXPECT_EQ(m.base_color, (Vec3{1, 0.5f, 1}));
    EXPECT_EQ(m.textures.roughness.texture, m.textures.metallic.texture);  // one decoding
    EXPECT_EQ(m.textures.roughness.channel, 1);
    EXPECT_EQ(m.textures.metallic.channel, 2);
    EXPECT_EQ(m.metallic, 0.75f);
    EXPECT_EQ(s.textures.size(), 2u);
}

TEST_F(SceneTextures, UntexturedMaterialsStayUntextured) {
    const Scene s = load(R"({"m": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}})");
    EXPECT_FALSE(s.materials[0].textured);
    EXPECT_TRUE(s.textures.empty());
}

TEST_F(SceneTextures, BadTexturesAreErrorsAtTheirKey) {
    EXPECT_NE(error_of(R"({"m": {"type": "diffuse", "kd": {"texture": "nope.png"}}})")
                  .find("scene.json: /materials/m/kd/texture: cannot open texture 'nope.png': no such file"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"m": {"type": "diffuse", "kd": [0.5, 0.5, 0.5], "normal_map": "nope.png"}})")
                  .find("/materials/m/normal_map: cannot open texture"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"m": {"type": "diffuse", "kd": {"texture": "rb.png", "scale": [2, 1, 1]}}})")
                  .find("/materials/m/kd/scale: kd components must lie in [0, 1]"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"m": {"type": "diffuse", "kd": {"texture": "rb.png", "tint": 1}}})")
                  .find("/materials/m/kd/tint: unknown key 'tint'"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"m": {"type": "diffuse", "kd": {"scale": [1, 1, 1]}}})")
                  .find("/materials/m/kd/texture: missing required key 'texture'"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"m": {"type": "diffuse", "kd": "rb.png"}})")
                  .find("/materials/m/kd: expected an array of 3 numbers or a texture"),
              std::string::npos);
    EXPECT_NE(
        error_of(R"({"m": {"type": "conductor", "ks": [1, 1, 1], "roughness": {"texture": "rb.png", "channel": "x"}}})")
            .find("/materials/m/roughness/channel: unknown channel 'x'"),
        std::string::npos);
    EXPECT_NE(error_of(R"({"m": {"type": "diffuse", "kd": [1, 1, 1], "alpha": {"texture": "rb.png", "cutoff": 2}}})")
                  .find("/materials/m/alpha/cutoff: cutoff must lie in [0, 1]"),
              std::string::npos);
    // An unreadable image: the error names the image file.
    tmp.write("broken.png", "\x89PNG\r\n\x1a\nbroken");
    EXPECT_NE(error_of(R"({"m": {"type": "diffuse", "kd": {"texture": "broken.png"}}})").find("broken.png: cannot"),
              std::string::npos);
}

TEST_F(SceneTextures, MtlMapsBecomeTexturesAndJoinTheSceneTable) {
    tmp.write("quad.mtl",
              "newmtl painted\nKd 0.2 0.2 0.2\nKs 0.1 0.1 0.1\nNs 20\nmap_Kd -clamp on .\\rb.png\nmap_Ks rb.png\n"
              "map_Ke g16.png\nbump -bm 0.25 g16.png\nnorm g16.png\nmap_d g16.png\n");
    Diagnostics mesh_diag;
    const LoadedMesh loaded = load_obj(tmp.path / "quad.obj", mesh_diag);
    ASSERT_EQ(loaded.materials.size(), 1u);
    const Material& m = loaded.materials[0];
    EXPECT_EQ(m.type, MaterialType::Phong);
    EXPECT_TRUE(m.textured);
    EXPECT_EQ(m.kd, Vec3{1.0f});  // the texture replaces Kd
    EXPECT_EQ(m.textures.kd.wrap_u, TextureWrap::Clamp);
    EXPECT_EQ(m.textures.ks.wrap_u, TextureWrap::Repeat);
    EXPECT_EQ(m.textures.bump_scale, 0.25f);
    // rb.png as colour (kd, ks); g16.png as colour (ke) and as data (bump, norm, map_d).
    ASSERT_EQ(loaded.textures.size(), 3u);
    EXPECT_EQ(m.textures.kd.texture, m.textures.ks.texture);
    EXPECT_EQ(m.textures.bump_map.texture, m.textures.normal_map.texture);
    EXPECT_EQ(m.textures.alpha.texture, m.textures.normal_map.texture);
    EXPECT_TRUE(m.textures.alpha_test);  // map_d is a cut-out at 0.5, applied quietly
    EXPECT_EQ(m.textures.alpha_cutoff, 0.5f);
    for (const std::string& w : mesh_diag.warnings) EXPECT_EQ(w.find("map_d"), std::string::npos) << w;
    EXPECT_NE(m.textures.ke.texture, m.textures.normal_map.texture);

    // Two objects of the file and a scene material on rb.png: rb.png is decoded once in the scene.
    const Scene s = load(R"({"m": {"type": "diffuse", "kd": {"texture": "rb.png"}}})",
                         R"([{"file": "quad.obj"}, {"file": "quad.obj"}, {"file": "quad.obj", "material": "m"}])");
    ASSERT_EQ(s.textures.size(), 3u);
    ASSERT_EQ(s.materials.size(), 3u);  // m, then the file's "painted" twice
    const Material& scene_m = s.materials[0];
    for (std::size_t i = 1; i < 3; ++i) {
        EXPECT_TRUE(s.materials[i].textured);
        EXPECT_EQ(s.materials[i].textures.kd.texture, scene_m.textures.kd.texture) << i;
        EXPECT_EQ(s.textures[s.materials[i].textures.bump_map.texture].encoding, TextureEncoding::Data);
    }
}

TEST_F(SceneTextures, MissingMtlTexturesWarnAndKeepTheConstant) {
    tmp.write(
        "quad.mtl",
        "newmtl painted\nKd 0.2 0.3 0.4\nmap_Kd missing.png\nnorm missing.png\nnewmtl other\nmap_Kd missing.png\n");
    Diagnostics mesh_diag;
    const LoadedMesh loaded = load_obj(tmp.path / "quad.obj", mesh_diag);
    ASSERT_FALSE(loaded.materials.empty());
    EXPECT_EQ(loaded.materials[0].kd, (Vec3{0.2f, 0.3f, 0.4f}));
    EXPECT_FALSE(loaded.materials[0].textured);
    EXPECT_TRUE(loaded.textures.empty());
    std::size_t warned = 0;
    for (const std::string& w : mesh_diag.warnings)
        warned += w.find("texture 'missing.png': no such file") != std::string::npos;
    EXPECT_EQ(warned, 1u) << "one warning per missing file";
}

}  // namespace
}  // namespace sombra
