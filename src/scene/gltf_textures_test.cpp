// glTF materials' textures (spec §12, §13): each texel lands where the
// file's TEXCOORD_0 (v = 0 at the image's top) puts it, from an external
// file, a GLB buffer view or a data URI; metallic-roughness channels and
// alpha masks reach the right slots; missing and escaping image paths.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base64.h"
#include "scene/cutout.h"
#include "scene/gltf_test_files.h"
#include "scene/image_test_files.h"
#include "scene/mesh_file.h"
#include "scene/polygon_test_files.h"

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
GltfFile textured_quad(nlohmann::json image, const std::string& alpha_mode = "OPAQUE") {
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
    expect_cut_beyond(load("MASK", 0.4, 1.0), 0.75f, "MASK 0.4");      // 1 − 0.8x < 0.4
    expect_cut_beyond(load("MASK", 0.4, 0.5), 0.25f, "factor 0.5");    // 0.5(1 − 0.8x) < 0.4
    expect_cut_beyond(load("BLEND", 0.9, 1.0), 0.625f, "BLEND at 0.5, its cutoff ignored");  // 1 − 0.8x < 0.5
    expect_cut_beyond(load("OPAQUE", 0.4, 0.1), 2.0f, "OPAQUE ignores alpha");
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
        EXPECT_NE(e.message().find("'../secret.png' lies outside the model's folder"), std::string::npos) << e.message();
    }
}

TEST(GltfTextures, ABrokenEmbeddedImageIsAnError) {
    TempFolder dir;
    const std::string junk = "\x89PNG\r\n\x1a\nthis is not a png";
    textured_quad({{"uri", "data:image/png;base64," + base64_encode(junk)}}).save(dir.path / "m.gltf");
    Diagnostics diag;
    EXPECT_THROW(load_mesh_file(dir.path / "m.gltf", diag), Error);
}

}  // namespace
}  // namespace sombra
