// EXT_texture_webp (spec §24): a WebP made in the test with libwebp's
// lossless encoder gives the same texels as the same image as PNG; the
// extension's image is preferred over the fallback source; a broken or
// oversized WebP is one error line.
#include <gtest/gtest.h>

#include <webp/encode.h>

#include "core/base64.h"
#include "io/gltf/gltf_test_files.h"
#include "io/images/image_test_files.h"
#include "io/images/texture_image.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

// 3 × 2 RGBA texels, rows from the top, alpha varying (never 0: the
// lossless encoder need not keep the colour of a transparent texel).
const std::vector<unsigned char> kRgba = {255, 0, 0,   255, 0,   255, 0,   51, 10,  20,  30, 128,
                                          0,   0, 255, 255, 255, 255, 255, 51, 200, 100, 50, 7};
constexpr int kWidth = 3, kHeight = 2;

std::string webp_lossless(const std::vector<unsigned char>& rgba, int width, int height) {
    std::uint8_t* out = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), width, height, width * 4, &out);
    EXPECT_GT(size, 0u);
    std::string bytes(reinterpret_cast<const char*>(out), size);
    WebPFree(out);
    return bytes;
}

std::string png(const TempFolder& dir, const std::vector<unsigned char>& rgba) {
    const std::filesystem::path file = dir.path / "t.png";
    testing::write_png_file(file, kWidth, kHeight, 4, 8, std::vector<std::uint16_t>(rgba.begin(), rgba.end()));
    const std::vector<unsigned char> bytes = testing::read_file_bytes(file);
    return {bytes.begin(), bytes.end()};
}

std::string data_uri(const std::string& mime, const std::string& bytes) {
    return "data:" + mime + ";base64," + base64_encode(bytes);
}

// A textured quad whose texture 0 is `texture`, over `images`.
GltfFile textured_quad(const nlohmann::json& texture, const nlohmann::json& images) {
    GltfFile f;
    const int p = f.add_positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int uv = f.add_uvs({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    f.add_mesh({{"POSITION", p}, {"TEXCOORD_0", uv}}, f.add_indices({0, 1, 2, 0, 2, 3}), 0);
    f.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    f.doc["textures"] = {texture};
    f.doc["images"] = images;
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    return f;
}

const Texture& base_color(const LoadedMesh& m) {
    const TextureRef& ref = m.materials.at(0).textures.base_color;
    EXPECT_TRUE(ref.is_set());
    return m.textures.at(ref.texture);
}

TEST(GltfWebp, ALosslessWebpGivesThePngsTexels) {
    TempFolder dir;
    const std::string webp = webp_lossless(kRgba, kWidth, kHeight);
    GltfFile plain = textured_quad({{"source", 0}}, {{{"uri", data_uri("image/png", png(dir, kRgba))}}});
    GltfFile required = textured_quad({{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}},
                                      {{{"uri", data_uri("image/webp", webp)}}});
    required.use_extension("EXT_texture_webp", true);
    Diagnostics diag;
    const LoadedMesh a = load_gltf(dir.write("plain.gltf", plain.gltf()), diag);
    const LoadedMesh b = load_gltf(dir.write("webp.gltf", required.gltf()), diag);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
    const Texture &ta = base_color(a), &tb = base_color(b);
    EXPECT_EQ(tb.width, kWidth);
    EXPECT_EQ(tb.height, kHeight);
    EXPECT_EQ(tb.channels, 4);
    EXPECT_EQ(ta.texels, tb.texels);

    // In a GLB's buffer view, too.
    GltfFile glb = textured_quad({{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}, nlohmann::json::array());
    glb.doc["images"] = {{{"bufferView", glb.add_view(webp.data(), webp.size())}, {"mimeType", "image/webp"}}};
    glb.use_extension("EXT_texture_webp", true);
    const LoadedMesh c = load_gltf(dir.write("webp.glb", glb.glb()), diag);
    EXPECT_EQ(base_color(c).texels, ta.texels);
}

// The extension's source wins over the texture's own, its fallback for
// readers without WebP (a different, black PNG here).
TEST(GltfWebp, TheWebpSourceIsPreferredOverTheFallback) {
    TempFolder dir;
    const std::vector<unsigned char> black(kRgba.size(), 0);
    GltfFile f = textured_quad({{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}},
                               {{{"uri", data_uri("image/png", png(dir, black))}},
                                {{"uri", data_uri("image/webp", webp_lossless(kRgba, kWidth, kHeight))}}});
    f.use_extension("EXT_texture_webp");
    GltfFile plain = textured_quad({{"source", 0}}, {{{"uri", data_uri("image/png", png(dir, kRgba))}}});
    Diagnostics diag;
    const LoadedMesh a = load_gltf(dir.write("plain.gltf", plain.gltf()), diag);
    const LoadedMesh b = load_gltf(dir.write("both.gltf", f.gltf()), diag);
    EXPECT_EQ(base_color(a).texels, base_color(b).texels);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
}

// A lossy WebP decodes too (its texels close to the original, not equal).
TEST(GltfWebp, ALossyWebpDecodes) {
    std::vector<unsigned char> rgb;
    for (int i = 0; i < 16 * 16; ++i) rgb.insert(rgb.end(), {200, 120, 40});
    std::uint8_t* out = nullptr;
    const std::size_t size = WebPEncodeRGB(rgb.data(), 16, 16, 16 * 3, 90.0f, &out);
    ASSERT_GT(size, 0u);
    const std::vector<unsigned char> bytes(out, out + size);
    WebPFree(out);
    const Texture t = decode_texture(bytes, TextureEncoding::Data, "lossy.webp");
    EXPECT_EQ(t.width, 16);
    EXPECT_EQ(t.channels, 3);
    EXPECT_NEAR(t.texels[0], 200.0f / 255.0f, 0.03f);
}

TEST(GltfWebp, BrokenOrOversizedWebpIsOneErrorLine) {
    const std::string good = webp_lossless(kRgba, kWidth, kHeight);
    // The lossless header's 14-bit width − 1 and height − 1 (after the
    // signature byte 0x2f at offset 20) set to 16383: 16384² RGBA texels.
    std::string huge = good;
    std::uint32_t bits = 0;
    std::memcpy(&bits, huge.data() + 21, 4);
    bits = (bits & ~((1u << 28) - 1)) | 16383u | (16383u << 14);
    std::memcpy(huge.data() + 21, &bits, 4);
    const struct {
        const char* name;
        std::string bytes;
        const char* message;
    } cases[] = {
        {"truncated", good.substr(0, good.size() - 6), "WebP"},
        {"header only", good.substr(0, 16), "cannot read the WebP header"},
        {"oversized", huge, "16384×16384 pixels"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const std::vector<unsigned char> bytes(c.bytes.begin(), c.bytes.end());
        try {
            decode_texture(bytes, TextureEncoding::Color, "t.webp");
            ADD_FAILURE() << "decoded";
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), "t.webp");
            EXPECT_NE(e.message().find(c.message), std::string::npos) << e.message();
        }
        // And through a glTF file: the error names the image.
        GltfFile f = textured_quad({{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}},
                                   {{{"uri", data_uri("image/webp", c.bytes)}}});
        f.use_extension("EXT_texture_webp", true);
        TempFolder dir;
        Diagnostics diag;
        try {
            load_gltf(dir.write("m.gltf", f.gltf()), diag);
            ADD_FAILURE() << "loaded";
        } catch (const Error& e) {
            EXPECT_NE(e.where().find("m.gltf"), std::string::npos) << e.where();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
    }
}

}  // namespace
}  // namespace sombra
