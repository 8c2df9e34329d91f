// glTF's material extensions beyond the core model (spec §13, §24):
// KHR_materials_transmission, KHR_materials_volume, KHR_materials_clearcoat
// and KHR_materials_sheen read into the pbr material's transmission,
// thickness, attenuation, coat and sheen, their textures into
// the right slots and channels, broken values refused by name, and what is
// not supported (thicknessTexture) named in one warning.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "io/gltf/gltf_test_files.h"
#include "io/images/image_test_files.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

// A 2×2 RGBA PNG beside the model, tex.png.
void write_texture(const TempFolder& dir) {
    testing::write_png_file(dir.path / "tex.png", 2, 2, 4, 8,
                            {255, 0, 0, 255, 0, 255, 0, 51, 0, 0, 255, 255, 255, 255, 255, 51});
}

// A unit quad with uvs whose material `material` (a glTF material object) names texture 0 (tex.png).
GltfFile quad(const nlohmann::json& material) {
    GltfFile f;
    const int p = f.add_positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int uv = f.add_uvs({{0.25f, 0.25f}, {0.75f, 0.25f}, {0.75f, 0.75f}, {0.25f, 0.75f}});
    f.add_mesh({{"POSITION", p}, {"TEXCOORD_0", uv}}, f.add_indices({0, 1, 2, 0, 2, 3}), 0);
    f.doc["materials"] = {material};
    f.doc["textures"] = {{{"source", 0}}};
    f.doc["images"] = {{{"uri", "tex.png"}}};
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    return f;
}

// Loads `f` (saved in dir), returning the first material; warnings into diag.
Material load(const TempFolder& dir, const GltfFile& f, Diagnostics& diag, LoadedMesh* mesh = nullptr) {
    f.save(dir.path / "m.gltf");
    LoadedMesh m = load_mesh_file(dir.path / "m.gltf", diag);
    if (mesh) *mesh = m;
    return m.materials.at(0);
}

TEST(GltfMaterialExtensions, TransmissionAndVolumeAsBlenderWritesThem) {
    TempFolder dir;
    write_texture(dir);
    GltfFile f =
        quad({{"extensions",
               {{"KHR_materials_transmission", {{"transmissionFactor", 0.75}, {"transmissionTexture", {{"index", 0}}}}},
                {"KHR_materials_volume",
                 {{"thicknessFactor", 0.1}, {"attenuationDistance", 2.5}, {"attenuationColor", {0.5, 0.25, 1.0}}}},
                {"KHR_materials_ior", {{"ior", 1.45}}}}}});
    f.use_extension("KHR_materials_transmission");
    f.use_extension("KHR_materials_volume");
    f.use_extension("KHR_materials_ior");
    Diagnostics diag;
    LoadedMesh mesh;
    const Material m = load(dir, f, diag, &mesh);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    EXPECT_FLOAT_EQ(m.transmission, 0.75f);
    EXPECT_FLOAT_EQ(m.thickness, 0.1f);
    EXPECT_FLOAT_EQ(m.attenuation_distance, 2.5f);
    EXPECT_EQ(m.attenuation_color, (Vec3{0.5f, 0.25f, 1.0f}));
    EXPECT_FLOAT_EQ(m.ior, 1.45f);
    ASSERT_TRUE(m.textures.transmission.is_set());
    EXPECT_EQ(m.textures.transmission.channel, 0);  // R
    EXPECT_EQ(mesh.textures[m.textures.transmission.texture].encoding, TextureEncoding::Data);
    EXPECT_TRUE(m.textured);
    // σ_a = −ln(colour)/distance.
    const Vec3 sigma = volume_absorption(m);
    EXPECT_NEAR(sigma.x, std::log(2.0) / 2.5, 1e-6);
    EXPECT_NEAR(sigma.y, std::log(4.0) / 2.5, 1e-6);
    EXPECT_EQ(sigma.z, 0.0f);

    // Without the extensions: glTF's core, opaque model.
    Diagnostics plain_diag;
    const Material plain = load(dir, quad(nlohmann::json::object()), plain_diag);
    EXPECT_EQ(plain.transmission, 0.0f);
    EXPECT_EQ(plain.thickness, 0.0f);
    EXPECT_EQ(plain.attenuation_distance, std::numeric_limits<float>::infinity());
    EXPECT_FALSE(plain.textures.transmission.is_set());
    EXPECT_EQ(volume_absorption(plain), Vec3{0.0f});
}

TEST(GltfMaterialExtensions, UnsupportedVolumePartsAreNamedOnce) {
    TempFolder dir;
    write_texture(dir);
    GltfFile f = quad({{"extensions",
                        {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                         {"KHR_materials_volume", {{"thicknessFactor", 1.0}, {"thicknessTexture", {{"index", 0}}}}}}}});
    f.use_extension("KHR_materials_transmission");
    f.use_extension("KHR_materials_volume");
    Diagnostics diag;
    const Material m = load(dir, f, diag);
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("thicknessTexture ignored"), std::string::npos) << diag.warnings[0];
    EXPECT_FLOAT_EQ(m.thickness, 1.0f);
    // An infinite attenuation distance (the default): no absorption.
    EXPECT_EQ(volume_absorption(m), Vec3{0.0f});
}

TEST(GltfMaterialExtensions, ClearcoatAndItsTextures) {
    TempFolder dir;
    write_texture(dir);
    GltfFile f = quad({{"extensions",
                        {{"KHR_materials_clearcoat",
                          {{"clearcoatFactor", 0.8},
                           {"clearcoatRoughnessFactor", 0.25},
                           {"clearcoatTexture", {{"index", 0}}},
                           {"clearcoatRoughnessTexture", {{"index", 0}}},
                           {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.4}}}}}}}});
    f.use_extension("KHR_materials_clearcoat");
    Diagnostics diag;
    LoadedMesh mesh;
    const Material m = load(dir, f, diag, &mesh);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    ASSERT_TRUE(m.textures.clearcoat_normal_map.is_set());
    EXPECT_FLOAT_EQ(m.textures.clearcoat_normal_scale, 0.4f);
    EXPECT_EQ(mesh.textures[m.textures.clearcoat_normal_map.texture].encoding, TextureEncoding::Data);
    EXPECT_FALSE(m.textures.normal_map.is_set());
    EXPECT_FLOAT_EQ(m.clearcoat, 0.8f);
    EXPECT_FLOAT_EQ(m.clearcoat_roughness, 0.25f);
    ASSERT_TRUE(m.textures.clearcoat.is_set());
    EXPECT_EQ(m.textures.clearcoat.channel, 0);  // R
    ASSERT_TRUE(m.textures.clearcoat_roughness.is_set());
    EXPECT_EQ(m.textures.clearcoat_roughness.channel, 1);  // G
    EXPECT_EQ(mesh.textures[m.textures.clearcoat.texture].encoding, TextureEncoding::Data);

    Diagnostics plain_diag;
    const Material plain = load(dir, quad(nlohmann::json::object()), plain_diag);
    EXPECT_EQ(plain.clearcoat, 0.0f);
    EXPECT_FALSE(plain.textures.clearcoat.is_set());
    EXPECT_FALSE(plain.textures.clearcoat_normal_map.is_set());
}

TEST(GltfMaterialExtensions, SheenAndItsTextures) {
    TempFolder dir;
    write_texture(dir);
    const nlohmann::json transform = {{"KHR_texture_transform", {{"scale", {2, 2}}}}};
    GltfFile f = quad({{"extensions",
                        {{"KHR_materials_sheen",
                          {{"sheenColorFactor", {0.9, 0.5, 0.25}},
                           {"sheenRoughnessFactor", 0.4},
                           {"sheenColorTexture", {{"index", 0}}},
                           {"sheenRoughnessTexture", {{"index", 0}, {"extensions", transform}}}}}}}});
    f.use_extension("KHR_materials_sheen");
    f.use_extension("KHR_texture_transform");
    Diagnostics diag;
    LoadedMesh mesh;
    const Material m = load(dir, f, diag, &mesh);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    EXPECT_EQ(m.sheen_color, (Vec3{0.9f, 0.5f, 0.25f}));
    EXPECT_FLOAT_EQ(m.sheen_roughness, 0.4f);
    ASSERT_TRUE(m.textures.sheen_color.is_set());
    EXPECT_EQ(mesh.textures[m.textures.sheen_color.texture].encoding, TextureEncoding::Color);  // sRGB
    ASSERT_TRUE(m.textures.sheen_roughness.is_set());
    EXPECT_EQ(m.textures.sheen_roughness.channel, 3);  // A
    EXPECT_EQ(mesh.textures[m.textures.sheen_roughness.texture].encoding, TextureEncoding::Data);
    EXPECT_FALSE(m.textures.sheen_color.transformed);
    ASSERT_TRUE(m.textures.sheen_roughness.transformed);
    EXPECT_FLOAT_EQ(m.textures.sheen_roughness.uv_transform.uu, 2.0f);
    EXPECT_TRUE(m.textured);

    // The defaults: colour 0 (no layer) and roughness 0; an empty extension is no sheen.
    GltfFile empty = quad({{"extensions", {{"KHR_materials_sheen", nlohmann::json::object()}}}});
    empty.use_extension("KHR_materials_sheen");
    Diagnostics empty_diag;
    const Material none = load(dir, empty, empty_diag);
    EXPECT_TRUE(empty_diag.warnings.empty()) << empty_diag.warnings[0];
    EXPECT_EQ(none.sheen_color, Vec3{0.0f});
    EXPECT_EQ(none.sheen_roughness, 0.0f);
    EXPECT_FALSE(none.textures.sheen_color.is_set());

    // Outside [0, 1]: clamped, with a warning naming the member.
    GltfFile bright = quad({{"extensions", {{"KHR_materials_sheen", {{"sheenColorFactor", {1.5, 0.5, -0.5}}}}}}});
    bright.use_extension("KHR_materials_sheen");
    Diagnostics bright_diag;
    const Material clamped = load(dir, bright, bright_diag);
    ASSERT_FALSE(bright_diag.warnings.empty());
    EXPECT_NE(bright_diag.warnings[0].find("sheenColorFactor outside [0, 1] clamped"), std::string::npos)
        << bright_diag.warnings[0];
    EXPECT_EQ(clamped.sheen_color, (Vec3{1.0f, 0.5f, 0.0f}));
}

TEST(GltfMaterialExtensions, SheenIsSupportedWhenRequired) {
    TempFolder dir;
    GltfFile f = quad({{"extensions", {{"KHR_materials_sheen", {{"sheenColorFactor", {1, 1, 1}}}}}}});
    f.use_extension("KHR_materials_sheen");
    f.doc["extensionsRequired"] = {"KHR_materials_sheen"};
    Diagnostics diag;
    EXPECT_EQ(load(dir, f, diag).sheen_color, Vec3{1.0f});
    for (const std::string& w : diag.warnings) EXPECT_EQ(w.find("KHR_materials_sheen"), std::string::npos) << w;
}

TEST(GltfMaterialExtensions, UnlitEmitsItsBaseColourOnly) {
    TempFolder dir;
    write_texture(dir);
    GltfFile f = quad(
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 1.0}}},
         {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}});
    f.use_extension("KHR_materials_unlit");
    Diagnostics diag;
    LoadedMesh mesh;
    const Material m = load(dir, f, diag, &mesh);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    EXPECT_EQ(m.type, MaterialType::Diffuse);
    EXPECT_EQ(m.kd, Vec3{0.0f});
    EXPECT_EQ(m.ke, (Vec3{0.5f, 0.25f, 1.0f}));
    ASSERT_TRUE(m.textures.ke.is_set());
    EXPECT_EQ(mesh.textures[m.textures.ke.texture].encoding, TextureEncoding::Color);  // sRGB, as the base colour
    EXPECT_FALSE(m.textures.metallic.is_set());
}

TEST(GltfMaterialExtensions, BrokenValuesAreRefusedByName) {
    TempFolder dir;
    write_texture(dir);
    for (const auto& [extension, member, value, message] :
         {std::tuple<const char*, const char*, nlohmann::json, const char*>{
              "KHR_materials_transmission", "transmissionFactor", "all", "transmissionFactor must be a number"},
          {"KHR_materials_transmission", "transmissionTexture", {{"index", 9}}, "transmissionTexture names texture 9"},
          {"KHR_materials_volume", "thicknessFactor", -1.0, "thicknessFactor must be a finite number >= 0"},
          {"KHR_materials_volume", "attenuationDistance", 0.0, "attenuationDistance must be a number > 0"},
          {"KHR_materials_volume", "attenuationColor", {1, 1}, "attenuationColor must be 3 numbers"},
          // The JSON type check names it first (gltf_json_types.cpp).
          {"KHR_materials_clearcoat", "clearcoatFactor", true, "clearcoatFactor"},
          {"KHR_materials_clearcoat",
           "clearcoatRoughnessTexture",
           {{"index", 3}},
           "clearcoatRoughnessTexture names texture 3"},
          {"KHR_materials_sheen", "sheenColorFactor", {1, 1}, "sheenColorFactor must be 3 numbers"},
          {"KHR_materials_sheen", "sheenColorFactor", {1, 1, 1, 1}, "sheenColorFactor must be 3 numbers"},
          {"KHR_materials_sheen", "sheenRoughnessTexture", {{"index", 3}}, "sheenRoughnessTexture names texture 3"},
          {"KHR_materials_sheen", "sheenColorTexture", {{"texCoord", 0}}, "sheenColorTexture needs a texture index"}}) {
        GltfFile bad = quad({{"extensions", {{extension, {{member, value}}}}}});
        bad.use_extension(extension);
        Diagnostics diag;
        try {
            load(dir, bad, diag);
            ADD_FAILURE() << member << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace sombra
