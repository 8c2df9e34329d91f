// glTF materials' textures (spec §12, §13): each texel lands where the
// file's TEXCOORD_0 (v = 0 at the image's top) puts it, from an external
// file, a GLB buffer view or a data URI; metallic-roughness channels and
// alpha masks reach the right slots; missing and escaping image paths.
#include <gtest/gtest.h>

#include <tuple>

#include <array>
#include <cmath>
#include <set>

#include "core/base64.h"
#include "io/gltf/gltf_test_files.h"
#include "io/images/image_test_files.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"
#include "scene/cutout.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

// A 2×2 RGBA PNG, rows from the top: red, green / blue, white; alpha 1 on the
// left column, 0.2 on the right (so a MASK at 0.5 cuts the right half).
std::string two_by_two_png(const TempFolder& dir) {
    const std::filesystem::path file = dir.path / "tex.png";
    testing::write_png_file(file, 2, 2, 4, 8, {255, 0, 0, 255, 0, 255, 0, 51, 0, 0, 255, 255, 255, 255, 255, 51});
    const std::vector<unsigned char> bytes = testing::read_file_bytes(file);
    return std::string(bytes.begin(), bytes.end());
}

// A unit quad whose four corners carry, in glTF's convention, the uv of the
// centre of one texel each: (0, 0) corner → top-left texel (red), (1, 0) →
// top-right (green), (1, 1) → bottom-right (white), (0, 1) → bottom-left (blue).
GltfFile textured_quad(const nlohmann::json& image, const std::string& alpha_mode = "OPAQUE") {
    GltfFile f;
    const int p = f.add_positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int uv = f.add_uvs({{0.25f, 0.25f}, {0.75f, 0.25f}, {0.75f, 0.75f}, {0.25f, 0.75f}});
    f.add_mesh({{"POSITION", p}, {"TEXCOORD_0", uv}}, f.add_indices({0, 1, 2, 0, 2, 3}), 0);
    f.doc["materials"] = {{{"name", "tex"},
                           {"alphaMode", alpha_mode},
                           {"pbrMetallicRoughness",
                            {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}}}}}}};
    f.doc["textures"] = {{{"source", 0}}};
    f.doc["images"] = {image};
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    return f;
}

// The texel colour each corner (by position) reads through the loaded mesh's uvs.
void expect_texels_where_the_file_puts_them(const LoadedMesh& m) {
    ASSERT_EQ(m.materials.size(), 1u);
    const TextureRef& ref = m.materials[0].textures.base_color;
    ASSERT_TRUE(ref.is_set());
    ASSERT_LT(ref.texture, m.textures.size());
    const Texture& t = m.textures[ref.texture];
    EXPECT_EQ(t.width, 2);
    EXPECT_TRUE(m.materials[0].textured);
    ASSERT_TRUE(m.mesh.has_uvs());
    int checked = 0;
    for (std::size_t tri = 0; tri < m.mesh.triangles.size(); ++tri)
        for (int c = 0; c < 3; ++c) {
            const Vec3 p = m.mesh.positions[m.mesh.triangles[tri][c]];
            const Vec2 uv = m.mesh.uvs[m.mesh.uv_indices[tri][c]];
            const Vec3 colour = rgb_of(eval_texture(t, uv));
            const Vec3 expected = p == Vec3{0, 0, 0}   ? Vec3{1, 0, 0}
                                  : p == Vec3{1, 0, 0} ? Vec3{0, 1, 0}
                                  : p == Vec3{1, 1, 0} ? Vec3{1, 1, 1}
                                                       : Vec3{0, 0, 1};
            EXPECT_EQ(colour, expected) << "corner at (" << p.x << ", " << p.y << ")";
            ++checked;
        }
    EXPECT_EQ(checked, 6);
}

TEST(GltfTextures, ExternalImageTexelsLandWhereTheFilePutsThem) {
    TempFolder dir;
    two_by_two_png(dir);
    textured_quad({{"uri", "tex.png"}}).save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedMesh m = load_mesh_file(dir.path / "m.gltf", diag);
    expect_texels_where_the_file_puts_them(m);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
}

TEST(GltfTextures, GlbBufferViewAndDataUriImagesDecodeTheSame) {
    TempFolder dir;
    const std::string png = two_by_two_png(dir);
    GltfFile glb = textured_quad(nullptr);
    glb.doc["images"] = {{{"bufferView", glb.add_view(png.data(), png.size())}, {"mimeType", "image/png"}}};
    glb.save(dir.path / "m.glb");
    Diagnostics diag;
    expect_texels_where_the_file_puts_them(load_mesh_file(dir.path / "m.glb", diag));

    textured_quad({{"uri", "data:image/png;base64," + base64_encode(png)}}).save(dir.path / "d.gltf");
    expect_texels_where_the_file_puts_them(load_mesh_file(dir.path / "d.gltf", diag));
}

TEST(GltfTextures, MetallicRoughnessChannelsAndAlphaMask) {
    TempFolder dir;
    two_by_two_png(dir);
    GltfFile f = textured_quad({{"uri", "tex.png"}}, "MASK");
    f.doc["materials"][0]["alphaCutoff"] = 0.4;
    f.save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedMesh m = load_mesh_file(dir.path / "m.gltf", diag);
    const MaterialTextures& t = m.materials[0].textures;
    EXPECT_EQ(t.roughness.channel, 1);  // G
    EXPECT_EQ(t.metallic.channel, 2);   // B
    ASSERT_TRUE(t.roughness.is_set());
    EXPECT_EQ(m.textures[t.roughness.texture].encoding, TextureEncoding::Data);
    ASSERT_TRUE(t.base_color.is_set());
    EXPECT_EQ(m.textures[t.base_color.texture].encoding, TextureEncoding::Color);
    // The alpha of the mask is the base colour image's A channel, at the file's cutoff.
    EXPECT_EQ(t.alpha.texture, t.base_color.texture);
    EXPECT_EQ(t.alpha.channel, 3);
    EXPECT_FLOAT_EQ(t.alpha_cutoff, 0.4f);
    EXPECT_TRUE(t.alpha_test);
    EXPECT_EQ(t.alpha_factor, 1.0f);
    // An opaque material has no cut-out.
    textured_quad({{"uri", "tex.png"}}).save(dir.path / "o.gltf");
    const MaterialTextures opaque = load_mesh_file(dir.path / "o.gltf", diag).materials[0].textures;
    EXPECT_FALSE(opaque.alpha.is_set());
    EXPECT_FALSE(opaque.alpha_test);
}

TEST(GltfTextures, SpecularExtensionSetsTheLayerAndItsTextures) {
    // KHR_materials_specular as Blender and gltf-transform write it: the
    // strength from specularTexture's A, the F0 colour from
    // specularColorTexture's RGB (sRGB), each times its factor; a colour
    // factor above 1 is kept (the BSDF clamps f0 at 1).
    TempFolder dir;
    two_by_two_png(dir);
    GltfFile f = textured_quad({{"uri", "tex.png"}});
    f.doc["materials"][0]["extensions"]["KHR_materials_specular"] = {
        {"specularFactor", 0.5},
        {"specularColorFactor", {2.0, 0.2, 0.0}},
        {"specularTexture", {{"index", 0}}},
        {"specularColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2, 2}}}}}}}}};
    f.use_extension("KHR_materials_specular");
    f.use_extension("KHR_texture_transform");
    f.save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedMesh m = load_mesh_file(dir.path / "m.gltf", diag);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];  // a supported extension: no complaint
    const Material& mat = m.materials[0];
    EXPECT_FLOAT_EQ(mat.specular, 0.5f);
    EXPECT_EQ(mat.specular_color, (Vec3{2.0f, 0.2f, 0.0f}));
    const MaterialTextures& t = mat.textures;
    ASSERT_TRUE(t.specular.is_set());
    EXPECT_EQ(t.specular.channel, 3);  // A
    EXPECT_EQ(m.textures[t.specular.texture].encoding, TextureEncoding::Data);
    ASSERT_TRUE(t.specular_color.is_set());
    EXPECT_EQ(m.textures[t.specular_color.texture].encoding, TextureEncoding::Color);
    EXPECT_TRUE(t.specular_color.transformed);
    EXPECT_FALSE(t.specular.transformed);

    // Without the extension the layer is glTF's core one.
    textured_quad({{"uri", "tex.png"}}).save(dir.path / "plain.gltf");
    const Material plain = load_mesh_file(dir.path / "plain.gltf", diag).materials[0];
    EXPECT_EQ(plain.specular, 1.0f);
    EXPECT_EQ(plain.specular_color, Vec3{1.0f});
    EXPECT_FALSE(plain.textures.specular.is_set());

    // Broken values are refused with the member's name.
    for (const auto& [member, value, message] :
         {std::tuple<const char*, nlohmann::json, const char*>{"specularFactor", "high",
                                                               "specularFactor must be a number"},
          {"specularColorFactor", {1, 1}, "specularColorFactor must be 3 numbers"},
          {"specularTexture", {{"index", 7}}, "specularTexture names texture 7"},
          {"specularColorTexture", {{"texCoord", 0}}, "specularColorTexture needs a texture index"}}) {
        GltfFile bad = textured_quad({{"uri", "tex.png"}});
        bad.doc["materials"][0]["extensions"]["KHR_materials_specular"] = {{member, value}};
        bad.save(dir.path / "bad.gltf");
        try {
            load_mesh_file(dir.path / "bad.gltf", diag);
            ADD_FAILURE() << member << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    }
}

// Where the surface of the quad at (x, y, 0) exists, by the loaded mesh's cut-outs.
bool exists_at(const LoadedMesh& m, float x, float y) {
    const Cutouts cutouts = make_cutouts(m.mesh, m.materials, m.textures);
    if (!cutouts.active()) return true;
    for (std::uint32_t tri = 0; tri < m.mesh.triangles.size(); ++tri) {
        float b1 = 0, b2 = 0;
        if (!point_barycentrics(m.mesh, tri, {x, y, 0}, b1, b2)) continue;
        if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
        return surface_exists(cutouts, tri, b1, b2);
    }
    ADD_FAILURE() << "(" << x << ", " << y << ") is not on the quad";
    return false;
}

TEST(GltfTextures, MaskCutsWhereFactorTimesImageAlphaIsBelowTheCutoff) {
    // Across the quad the image's alpha falls linearly from 1 (x = 0, the
    // left texels' centres) to 0.2 (x = 1): alpha(x) = f·(1 − 0.8x) for a
    // baseColorFactor alpha f.
    TempFolder dir;
    two_by_two_png(dir);
    const auto load = [&](const std::string& mode, double cutoff, double factor) {
        GltfFile f = textured_quad({{"uri", "tex.png"}}, mode);
        f.doc["materials"][0]["alphaCutoff"] = cutoff;
        f.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1, factor};
        f.save(dir.path / "m.gltf");
        Diagnostics diag;
        LoadedMesh m = load_mesh_file(dir.path / "m.gltf", diag);
        for (const std::string& w : diag.warnings) EXPECT_EQ(w.find("alpha"), std::string::npos) << w;
        return m;
    };
    const auto expect_cut_beyond = [&](const LoadedMesh& m, float edge, const std::string& what) {
        for (float x = 0.025f; x < 1.0f; x += 0.05f) {
            if (std::fabs(x - edge) < 1e-3f) continue;
            EXPECT_EQ(exists_at(m, x, 0.3f), x < edge) << what << " at x = " << x;
        }
    };
    expect_cut_beyond(load("MASK", 0.4, 1.0), 0.75f, "MASK 0.4");                            // 1 − 0.8x < 0.4
    expect_cut_beyond(load("MASK", 0.4, 0.5), 0.25f, "factor 0.5");                          // 0.5(1 − 0.8x) < 0.4
    expect_cut_beyond(load("BLEND", 0.9, 1.0), 0.625f, "BLEND at 0.5, its cutoff ignored");  // 1 − 0.8x < 0.5
    expect_cut_beyond(load("OPAQUE", 0.4, 0.1), 2.0f, "OPAQUE ignores alpha");
}

TEST(GltfTextures, VertexColourAlphaMultipliesTheMask) {
    // No image: COLOR_0's alpha 1 at x = 0 and 0 at x = 1, times a factor of
    // 0.8, is 0.8(1 − x); a MASK at 0.5 cuts x > 0.375.
    TempFolder dir;
    GltfFile f;
    const int p = f.add_positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const std::vector<float> rgba = {1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 0, 1, 1, 1, 1};
    const int colours = f.add_array(rgba, gltf_test::kFloat, 4, "VEC4");
    f.add_mesh({{"POSITION", p}, {"COLOR_0", colours}}, f.add_indices({0, 1, 2, 0, 2, 3}), 0);
    f.doc["materials"] = {{{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.8}}}}}};
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    f.save(dir.path / "c.gltf");
    Diagnostics diag;
    const LoadedMesh m = load_mesh_file(dir.path / "c.gltf", diag);
    ASSERT_TRUE(m.mesh.has_colors());
    for (int k = 0; k < 20; ++k) {
        const float x = 0.02f + 0.05f * static_cast<float>(k);  // never within 0.005 of the edge
        EXPECT_EQ(exists_at(m, x, 0.3f), x < 0.375f) << "x = " << x;
    }
}

TEST(GltfTextures, MissingImageIsAWarningAndAPathOutOfTheFolderAnError) {
    TempFolder dir;
    textured_quad({{"uri", "no%20such.png"}}).save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedMesh m = load_mesh_file(dir.path / "m.gltf", diag);
    EXPECT_FALSE(m.materials[0].textures.base_color.is_set());
    EXPECT_FALSE(m.materials[0].textured);
    ASSERT_FALSE(diag.warnings.empty());
    EXPECT_NE(diag.warnings[0].find("'no%20such.png' not found: the material's constant is used"), std::string::npos)
        << diag.warnings[0];

    textured_quad({{"uri", "../secret.png"}}).save(dir.path / "e.gltf");
    try {
        load_mesh_file(dir.path / "e.gltf", diag);
        ADD_FAILURE() << "a path out of the model's folder loaded";
    } catch (const Error& e) {
        EXPECT_NE(e.message().find("'../secret.png' lies outside the model's folder"), std::string::npos)
            << e.message();
    }
}

TEST(GltfTextures, ABrokenEmbeddedImageIsAnError) {
    TempFolder dir;
    const std::string junk = "\x89PNG\r\n\x1a\nthis is not a png";
    textured_quad({{"uri", "data:image/png;base64," + base64_encode(junk)}}).save(dir.path / "m.gltf");
    Diagnostics diag;
    EXPECT_THROW(load_mesh_file(dir.path / "m.gltf", diag), Error);
}

// A 4×4 RGB image, texel (column i, row j from the top) = (10 + 60i, 10 + 60j, 128):
// no two alike, so a texel seen names where the lookup went.
void write_four_by_four_png(const std::filesystem::path& file) {
    std::vector<std::uint16_t> values;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            values.insert(values.end(), {std::uint16_t(10 + 60 * i), std::uint16_t(10 + 60 * j), 128});
    testing::write_png_file(file, 4, 4, 3, 8, values);
}

// textured_quad with that image and `transform` as the base colour's KHR_texture_transform.
GltfFile transformed_quad(const nlohmann::json& transform) {
    GltfFile f = textured_quad({{"uri", "grid.png"}});
    nlohmann::json& base_colour = f.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"];
    base_colour["extensions"]["KHR_texture_transform"] = transform;
    f.use_extension("KHR_texture_transform");
    return f;
}

// Where glTF's uv lands under offset, rotation, scale: the extension's GLSL,
// its column-major mat3s written out as they appear in the specification,
// multiplied as 3×3 matrices (translation · rotation · scale).
Vec2 spec_transformed_uv(Vec2 uv, Vec2 offset, double rotation, Vec2 scale) {
    using Mat3 = std::array<std::array<double, 3>, 3>;  // [column][row], as GLSL
    const double c = std::cos(rotation), s = std::sin(rotation);
    const Mat3 translation{{{1, 0, 0}, {0, 1, 0}, {offset.x, offset.y, 1}}};
    const Mat3 rotate{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
    const Mat3 scaling{{{scale.x, 0, 0}, {0, scale.y, 0}, {0, 0, 1}}};
    const auto multiply = [](const Mat3& a, const Mat3& b) {
        Mat3 out{};
        for (int col = 0; col < 3; ++col)
            for (int row = 0; row < 3; ++row)
                for (int k = 0; k < 3; ++k) out[col][row] += a[k][row] * b[col][k];
        return out;
    };
    const Mat3 m = multiply(multiply(translation, rotate), scaling);
    const double in[3] = {uv.x, uv.y, 1};
    double out[2] = {0, 0};
    for (int row = 0; row < 2; ++row)
        for (int k = 0; k < 3; ++k) out[row] += m[k][row] * in[k];
    return {float(out[0]), float(out[1])};
}

// The base colour texture of `m` read at glTF uv (u, v): through the loaded
// reference, at sombra's stored (u, 1 − v), as the renderer reads it.
Rgba lookup_at_gltf_uv(const LoadedMesh& m, Vec2 uv) {
    return eval_texture_ref(m.textures, m.materials[0].textures.base_color, Vec2{uv.x, 1.0f - uv.y});
}

TEST(GltfTextures, TextureTransformMovesEachLookupWhereTheSpecificationSays) {
    TempFolder dir;
    write_four_by_four_png(dir.path / "grid.png");
    // A quarter turn, unequal scales and an offset: every glTF uv below lands
    // on a texel centre ((i + ½)/4, (j + ½)/4), a different one each time.
    const Vec2 offset{0.125f, 0.875f}, scale{2.0f, 0.5f};
    const double quarter_turn = std::acos(-1.0) / 2;
    transformed_quad({{"offset", {offset.x, offset.y}}, {"rotation", quarter_turn}, {"scale", {scale.x, scale.y}}})
        .save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedMesh m = load_mesh_file(dir.path / "m.gltf", diag);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
    ASSERT_TRUE(m.materials[0].textures.base_color.is_set());
    EXPECT_TRUE(m.materials[0].textures.base_color.transformed);
    std::set<std::pair<int, int>> seen;
    for (const float u : {0.0f, 0.125f, 0.25f, 0.375f})
        for (const float v : {0.0f, 0.5f, 1.0f, 1.5f}) {
            const Vec2 target = spec_transformed_uv({u, v}, offset, quarter_turn, scale);
            const int i = int(std::floor(target.x * 4)), j = int(std::floor(target.y * 4));
            ASSERT_TRUE(i >= 0 && i < 4 && j >= 0 && j < 4) << "the test's uvs must stay inside the image";
            ASSERT_NEAR(target.x * 4, float(i) + 0.5f, 1e-5f);
            ASSERT_NEAR(target.y * 4, float(j) + 0.5f, 1e-5f);
            seen.insert({i, j});
            const Rgba got = lookup_at_gltf_uv(m, {u, v});
            // Texel centres are exact up to the rounding of cos(π/2) and the sums.
            EXPECT_NEAR(got[0], srgb_decode(unsigned(10 + 60 * i), 255), 1e-5f) << "glTF uv (" << u << ", " << v << ")";
            EXPECT_NEAR(got[1], srgb_decode(unsigned(10 + 60 * j), 255), 1e-5f) << "glTF uv (" << u << ", " << v << ")";
        }
    EXPECT_EQ(seen.size(), 16u);

    // Any rotation, between texel centres: the bilinear lookup at the
    // specification's uv, written in sombra's convention (u, 1 − v).
    const Vec2 offset2{-0.3f, 0.2f}, scale2{1.7f, -0.6f};
    const double rotation2 = 0.3;
    transformed_quad({{"offset", {offset2.x, offset2.y}}, {"rotation", rotation2}, {"scale", {scale2.x, scale2.y}}})
        .save(dir.path / "n.gltf");
    const LoadedMesh n = load_mesh_file(dir.path / "n.gltf", diag);
    const Texture& grid = n.textures[n.materials[0].textures.base_color.texture];
    for (const Vec2 uv : {Vec2{0.1f, 0.2f}, Vec2{0.7f, 0.35f}, Vec2{0.45f, 0.9f}, Vec2{0.95f, 0.05f}}) {
        const Vec2 target = spec_transformed_uv(uv, offset2, rotation2, scale2);
        const Rgba want = eval_texture(grid, {target.x, 1.0f - target.y});
        const Rgba got = lookup_at_gltf_uv(n, uv);
        // The texture changes by at most one texel step (~0.7) per 1/4 of uv;
        // float rounding of the two matrix forms stays below 1e-6 in uv.
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-5f) << "glTF uv (" << uv.x << ", " << uv.y << ")";
    }
}

TEST(GltfTextures, IdentityTextureTransformLooksUpExactlyAsNone) {
    TempFolder dir;
    write_four_by_four_png(dir.path / "grid.png");
    transformed_quad({{"offset", {0, 0}}, {"rotation", 0}, {"scale", {1, 1}}}).save(dir.path / "identity.gltf");
    GltfFile plain = textured_quad({{"uri", "grid.png"}});
    plain.save(dir.path / "plain.gltf");
    Diagnostics diag;
    const LoadedMesh a = load_mesh_file(dir.path / "identity.gltf", diag);
    const LoadedMesh b = load_mesh_file(dir.path / "plain.gltf", diag);
    EXPECT_FALSE(a.materials[0].textures.base_color.transformed);
    for (const Vec2 uv : {Vec2{0.1f, 0.2f}, Vec2{0.7f, 0.35f}, Vec2{0.4999f, 0.9f}, Vec2{-3.3f, 7.05f}}) {
        EXPECT_EQ(lookup_at_gltf_uv(a, uv), lookup_at_gltf_uv(b, uv));
        // ... and exactly the texture itself at the stored uv.
        EXPECT_EQ(lookup_at_gltf_uv(b, uv), eval_texture(b.textures[0], Vec2{uv.x, 1.0f - uv.y}));
    }
}

TEST(GltfTextures, ATexCoordOverrideInTheTransformChoosesTheSet) {
    // Spec §24: the extension's texCoord replaces the reference's; set 1 is
    // read, 4 (beyond TEXCOORD_3) is not applied, with a warning.
    TempFolder dir;
    write_four_by_four_png(dir.path / "grid.png");
    for (const int set : {1, 4}) {
        SCOPED_TRACE(set);
        transformed_quad({{"offset", {0.5, 0}}, {"texCoord", set}}).save(dir.path / "m.gltf");
        Diagnostics diag;
        const LoadedMesh m = load_mesh_file(dir.path / "m.gltf", diag);
        const TextureRef& base = m.materials[0].textures.base_color;
        EXPECT_EQ(base.is_set(), set == 1);
        EXPECT_EQ(base.uv_set, set == 1 ? 1 : 0);
        EXPECT_EQ(m.materials[0].textures.metallic.uv_set, 0);  // its own texCoord, 0
        // Set 1 on a primitive that has only TEXCOORD_0 is the other warning.
        ASSERT_EQ(diag.warnings.size(), 1u);
        EXPECT_NE(diag.warnings[0].find(set == 1 ? "1 primitives lack a TEXCOORD_n" : "beyond TEXCOORD_3"),
                  std::string::npos)
            << diag.warnings[0];
    }
}

// The warning counts texture references: metallicRoughness fills two slots
// (roughness, metallic) but is one reference.
TEST(GltfTextures, TheTexCoordWarningCountsReferences) {
    TempFolder dir;
    two_by_two_png(dir);
    for (const bool both : {false, true}) {
        GltfFile f = textured_quad({{"uri", "tex.png"}});
        f.doc["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"]["texCoord"] = 4;
        if (both) f.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 9;
        Diagnostics diag;
        load_mesh_file(dir.write("m.gltf", f.gltf()), diag);
        ASSERT_EQ(diag.warnings.size(), 1u);
        EXPECT_EQ(diag.warnings[0].find(std::string(both ? "2" : "1") + " texture references use a TEXCOORD"),
                  diag.warnings[0].find(": ") + 2)
            << diag.warnings[0];
    }
}

}  // namespace
}  // namespace sombra
