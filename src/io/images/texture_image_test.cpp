// Textures (spec §12): bilinear lookups and wrap modes on tiny textures with
// exact values, sRGB decoding against the standard's formula, every image
// format read back value for value, and broken, truncated or oversized
// images refused with one-line errors.
#include "scene/texture.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "io/images/image_test_files.h"
#include "io/images/stb_guards.h"
#include "io/images/texture_image.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using testing::TempFolder;
using testing::write_png_file;
using testing::write_stb_file;

// A grey data texture of width × height values given from the TOP row.
Texture grey(int width, int height, std::vector<float> values) {
    Texture t;
    t.source = "test";
    t.encoding = TextureEncoding::Data;
    t.width = width;
    t.height = height;
    t.channels = 1;
    t.texels = std::move(values);
    return t;
}

// 2×2: bottom row a = 0, b = 1; top row c = 2, d = 4.
const Texture kSquare = grey(2, 2, {2, 4, 0, 1});

float at(const Texture& t, float u, float v, TextureWrap wrap = TextureWrap::Repeat) {
    return eval_texture(t, {u, v}, wrap, wrap)[0];
}

TEST(Texture, TexelCentresGiveTheTexelsAndBilinearBlendsBetween) {
    EXPECT_EQ(at(kSquare, 0.25f, 0.25f), 0.0f);  // v = 0 is the bottom row
    EXPECT_EQ(at(kSquare, 0.75f, 0.25f), 1.0f);
    EXPECT_EQ(at(kSquare, 0.25f, 0.75f), 2.0f);
    EXPECT_EQ(at(kSquare, 0.75f, 0.75f), 4.0f);
    EXPECT_EQ(at(kSquare, 0.5f, 0.5f), 1.75f);     // (0 + 1 + 2 + 4) / 4
    EXPECT_EQ(at(kSquare, 0.375f, 0.25f), 0.25f);  // a quarter of the way from a to b
    EXPECT_EQ(at(kSquare, 0.25f, 0.625f), 1.5f);   // three quarters from a to c
    EXPECT_EQ(at(kSquare, 0.625f, 0.375f), 0.75f * (0.25f * 0 + 0.75f * 1) + 0.25f * (0.25f * 2 + 0.75f * 4));
}

TEST(Texture, RepeatClampAndMirrorWrapAsTheirNamesSay) {
    // At the left edge, u = 0, halfway between texel 0's centre and the texel left of it.
    EXPECT_EQ(at(kSquare, 0.0f, 0.25f, TextureWrap::Repeat), 0.5f);  // its neighbour is texel 1 (b)
    EXPECT_EQ(at(kSquare, 0.0f, 0.25f, TextureWrap::Clamp), 0.0f);
    EXPECT_EQ(at(kSquare, 0.0f, 0.25f, TextureWrap::MirroredRepeat), 0.0f);
    // One texel beyond each edge.
    EXPECT_EQ(at(kSquare, -0.25f, 0.25f, TextureWrap::Repeat), 1.0f);
    EXPECT_EQ(at(kSquare, -0.25f, 0.25f, TextureWrap::Clamp), 0.0f);
    EXPECT_EQ(at(kSquare, -0.25f, 0.25f, TextureWrap::MirroredRepeat), 0.0f);
    EXPECT_EQ(at(kSquare, 1.25f, 0.25f, TextureWrap::Repeat), 0.0f);
    EXPECT_EQ(at(kSquare, 1.25f, 0.25f, TextureWrap::Clamp), 1.0f);
    EXPECT_EQ(at(kSquare, 1.25f, 0.25f, TextureWrap::MirroredRepeat), 1.0f);
    // Whole periods away; mirrored repeat's period is 2.
    EXPECT_EQ(at(kSquare, 3.75f, -1.75f, TextureWrap::Repeat), 1.0f);
    EXPECT_EQ(at(kSquare, 2.25f, 0.25f, TextureWrap::MirroredRepeat), 0.0f);
    EXPECT_EQ(at(kSquare, 1.75f, 0.25f, TextureWrap::MirroredRepeat), 0.0f);  // 2 − 1.75 = 0.25
    EXPECT_EQ(at(kSquare, 100.0f, 0.75f, TextureWrap::Clamp), 4.0f);
    // Each axis its own mode.
    EXPECT_EQ(eval_texture(kSquare, {1.25f, 1.25f}, TextureWrap::Clamp, TextureWrap::Repeat)[0], 1.0f);
    EXPECT_EQ(eval_texture(kSquare, {1.25f, 1.25f}, TextureWrap::Repeat, TextureWrap::Clamp)[0], 2.0f);
    // Non-finite coordinates read as 0.
    EXPECT_EQ(at(kSquare, NAN, 0.25f, TextureWrap::Clamp), 0.0f);
    EXPECT_EQ(at(kSquare, INFINITY, 0.25f, TextureWrap::Repeat), 0.5f);
}

TEST(Texture, GreyAndAlphaExpandToRgba) {
    Texture two = grey(1, 1, {0.25f, 0.5f});
    two.channels = 2;
    EXPECT_EQ(eval_texture(two, {0.5f, 0.5f}), (Rgba{0.25f, 0.25f, 0.25f, 0.5f}));
    Texture three = grey(1, 1, {0.1f, 0.2f, 0.3f});
    three.channels = 3;
    EXPECT_EQ(eval_texture(three, {0.5f, 0.5f}), (Rgba{0.1f, 0.2f, 0.3f, 1.0f}));
}

// The sRGB EOTF written out from IEC 61966-2-1, in double.
double srgb_reference(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

TEST(Texture, EightBitColourIsSrgbDecodedAtEveryCodeAndDataIsNot) {
    TempFolder tmp;
    std::vector<std::uint16_t> codes;  // 256 × 1 grey + alpha: value c, alpha c
    for (int c = 0; c < 256; ++c)
        codes.insert(codes.end(), {static_cast<std::uint16_t>(c), static_cast<std::uint16_t>(c)});
    write_png_file(tmp.path / "ramp.png", 256, 1, 2, 8, codes);
    const Texture colour = read_texture_file(tmp.path / "ramp.png", TextureEncoding::Color);
    const Texture data = read_texture_file(tmp.path / "ramp.png", TextureEncoding::Data);
    ASSERT_EQ(colour.channels, 2);
    ASSERT_EQ(colour.texels.size(), 512u);
    for (int c = 0; c < 256; ++c) {
        const float expected = static_cast<float>(srgb_reference(c / 255.0));
        EXPECT_EQ(colour.texels[2 * c], expected) << "code " << c;
        EXPECT_EQ(colour.texels[2 * c + 1], static_cast<float>(c) / 255.0f)
            << "alpha is never sRGB-decoded, code " << c;
        EXPECT_EQ(data.texels[2 * c], static_cast<float>(c) / 255.0f) << "code " << c;
    }
    // A few values known to a few digits: the curve's join and its midpoint.
    EXPECT_NEAR(srgb_to_linear(0.04045f), 0.0031308f, 1e-7f);
    EXPECT_NEAR(srgb_to_linear(0.5f), 0.2140411f, 1e-6f);
    EXPECT_EQ(srgb_to_linear(1.0f), 1.0f);
}

TEST(Texture, SixteenBitPngKeepsSixteenBits) {
    TempFolder tmp;
    const std::vector<std::uint16_t> values{0, 1, 257, 32768, 65534, 65535};
    write_png_file(tmp.path / "deep.png", 3, 2, 1, 16, values);
    const Texture data = read_texture_file(tmp.path / "deep.png", TextureEncoding::Data);
    const Texture colour = read_texture_file(tmp.path / "deep.png", TextureEncoding::Color);
    ASSERT_EQ(data.width, 3);
    ASSERT_EQ(data.height, 2);
    for (std::size_t i = 0; i < values.size(); ++i) {
        EXPECT_EQ(data.texels[i], static_cast<float>(values[i]) / 65535.0f) << i;
        EXPECT_EQ(colour.texels[i], static_cast<float>(srgb_reference(values[i] / 65535.0))) << i;
    }
    EXPECT_GT(data.texels[1], 0.0f);  // 1/65535: lost at 8 bits
    EXPECT_LT(data.texels[4], 1.0f);
}

TEST(Texture, SixteenBitColourIsSrgbDecodedAtEveryCode) {
    // Every code once, grey + alpha (256 × 256): large enough that decoding
    // goes through a table of the 65536 codes, which must give the formula's floats.
    TempFolder tmp;
    std::vector<std::uint16_t> codes;
    for (int c = 0; c < 65536; ++c)
        codes.insert(codes.end(), {static_cast<std::uint16_t>(c), static_cast<std::uint16_t>(65535 - c)});
    write_png_file(tmp.path / "all.png", 256, 256, 2, 16, codes);
    const Texture colour = read_texture_file(tmp.path / "all.png", TextureEncoding::Color);
    ASSERT_EQ(colour.texels.size(), codes.size());
    int wrong = 0;
    for (std::size_t i = 0; i < codes.size(); i += 2) {
        wrong += colour.texels[i] != static_cast<float>(srgb_reference(codes[i] / 65535.0));
        wrong += colour.texels[i + 1] != static_cast<float>(codes[i + 1]) / 65535.0f;
    }
    EXPECT_EQ(wrong, 0);
}

TEST(Texture, TgaBmpAndJpegReadBack) {
    TempFolder tmp;
    // 2×2 RGB, top row red, green; bottom row blue, white.
    const std::vector<unsigned char> rgb{255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    for (const char* format : {"tga", "bmp"}) {
        const auto file = tmp.path / (std::string("t.") + format);
        write_stb_file(file, format, 2, 2, 3, rgb);
        const Texture t = read_texture_file(file, TextureEncoding::Data);
        ASSERT_EQ(t.channels, 3) << format;
        ASSERT_EQ(t.texels.size(), 12u) << format;
        for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_EQ(t.texels[i], rgb[i] / 255.0f) << format << " " << i;
        // Bottom-left in uv is the image's bottom-left pixel: blue.
        EXPECT_EQ(eval_texture(t, {0.25f, 0.25f}), (Rgba{0, 0, 1, 1})) << format;
    }
    // JPEG is lossy: a flat 16×16 colour comes back within a few codes.
    std::vector<unsigned char> flat;
    for (int i = 0; i < 256; ++i) flat.insert(flat.end(), {200, 100, 50});
    write_stb_file(tmp.path / "flat.jpg", "jpg", 16, 16, 3, flat);
    const Texture jpeg = read_texture_file(tmp.path / "flat.jpg", TextureEncoding::Data);
    ASSERT_EQ(jpeg.texels.size(), 768u);
    for (std::size_t i = 0; i < jpeg.texels.size(); ++i) EXPECT_NEAR(jpeg.texels[i] * 255.0f, flat[i], 3.0f) << i;
}

TEST(Texture, DecodeFromMemoryNamesTheSource) {
    TempFolder tmp;
    write_png_file(tmp.path / "one.png", 1, 1, 3, 8, {255, 128, 0});
    const std::vector<unsigned char> bytes = testing::read_file_bytes(tmp.path / "one.png");
    const Texture t = decode_texture(bytes, TextureEncoding::Data, "model.glb: /images/0");
    EXPECT_EQ(t.source, "model.glb: /images/0");
    EXPECT_EQ(t.texels, (std::vector<float>{1.0f, 128 / 255.0f, 0.0f}));
    try {
        decode_texture(std::vector<unsigned char>(bytes.begin(), bytes.begin() + 20), TextureEncoding::Data,
                       "m.glb: /images/1");
        ADD_FAILURE() << "a truncated buffer decoded";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "m.glb: /images/1");
    }
}

// A zero-length IDAT chunk is legal; before the image's data it would make
// stb_image memcpy to a null buffer (fuzz_texture), so the decoder drops it.
TEST(Texture, EmptyIdatChunksBeforeTheDataAreDroppedAndTheImageReadsTheSame) {
    TempFolder tmp;
    std::vector<std::uint16_t> noise(5 * 3 * 3);
    for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<std::uint16_t>((i * 97 + 13) % 256);
    write_png_file(tmp.path / "plain.png", 5, 3, 3, 8, noise);
    const std::vector<unsigned char> plain = testing::read_file_bytes(tmp.path / "plain.png");
    EXPECT_FALSE(png_without_leading_empty_idat(plain).has_value());

    // length 0, "IDAT", the CRC-32 of "IDAT"
    const std::vector<unsigned char> empty_idat{0, 0, 0, 0, 'I', 'D', 'A', 'T', 0x35, 0xaf, 0x06, 0x1e};
    const std::string text(plain.begin(), plain.end());
    const std::size_t first_idat = text.find("IDAT") - 4, iend = text.find("IEND") - 4;
    std::vector<unsigned char> padded(plain.begin(), plain.begin() + first_idat);
    for (int i = 0; i < 2; ++i) padded.insert(padded.end(), empty_idat.begin(), empty_idat.end());
    padded.insert(padded.end(), plain.begin() + first_idat, plain.begin() + iend);
    padded.insert(padded.end(), empty_idat.begin(), empty_idat.end());  // after the data: stb copes
    padded.insert(padded.end(), plain.begin() + iend, plain.end());

    const std::optional<std::vector<unsigned char>> mended = png_without_leading_empty_idat(padded);
    ASSERT_TRUE(mended.has_value());
    std::vector<unsigned char> expected(plain.begin(), plain.begin() + iend);
    expected.insert(expected.end(), empty_idat.begin(), empty_idat.end());
    expected.insert(expected.end(), plain.begin() + iend, plain.end());
    EXPECT_EQ(*mended, expected);
    EXPECT_EQ(decode_texture(padded, TextureEncoding::Data, "padded").texels,
              decode_texture(plain, TextureEncoding::Data, "plain").texels);
}

// The message `read_texture_file` gives for the file, which must fail.
std::string error_of(const std::filesystem::path& file) {
    try {
        read_texture_file(file, TextureEncoding::Color);
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), file.string());
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        return e.message();
    }
    ADD_FAILURE() << file << " loaded";
    return {};
}

TEST(Texture, BrokenTruncatedAndHugeImagesAreOneLineErrors) {
    TempFolder tmp;
    std::vector<std::uint16_t> noise;
    for (int i = 0; i < 64 * 64 * 3; ++i) noise.push_back(static_cast<std::uint16_t>((i * 7919) % 251));
    write_png_file(tmp.path / "full.png", 64, 64, 3, 8, noise);
    const std::vector<unsigned char> png = testing::read_file_bytes(tmp.path / "full.png");
    std::vector<unsigned char> noise8(noise.begin(), noise.end());
    write_stb_file(tmp.path / "full.jpg", "jpg", 64, 64, 3, noise8);
    write_stb_file(tmp.path / "full.tga", "tga", 64, 64, 3, noise8);
    write_stb_file(tmp.path / "full.bmp", "bmp", 64, 64, 3, noise8);
    const auto half = [&](const char* name) {
        const std::vector<unsigned char> b = testing::read_file_bytes(tmp.path / name);
        return tmp.write(std::string("half-") + name,
                         std::string(b.begin(), b.begin() + static_cast<long>(b.size() / 2)));
    };
    EXPECT_NE(error_of(half("full.png")).find("PNG"), std::string::npos);
    // An IDAT chunk claiming 1 GiB: stb would grow its buffer to that before reading (fuzz_gltf).
    std::string claiming(png.begin(), png.end());
    const std::size_t idat = claiming.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    claiming.replace(idat - 4, 4, std::string("\x40\x00\x00\x00", 4));
    EXPECT_EQ(error_of(tmp.write("claims.png", claiming)),
              "PNG file is truncated: an IDAT chunk claims 1073741824 bytes, " +
                  std::to_string(claiming.size() - idat - 4) + " are left");
    EXPECT_NE(error_of(half("full.jpg")).find("JPEG"), std::string::npos);
    EXPECT_NE(error_of(half("full.tga")).find("TGA"), std::string::npos);
    EXPECT_NE(error_of(half("full.bmp")).find("BMP"), std::string::npos);

    // Headers claiming more than the limits, refused before any pixel is decoded.
    EXPECT_NE(error_of(tmp.write("wide.png", testing::png_claiming(100000, 1))).find("more than the limit"),
              std::string::npos);
    EXPECT_NE(error_of(tmp.write("big.png", testing::png_claiming(16000, 16000))).find("more than the limit"),
              std::string::npos);
    EXPECT_NE(error_of(tmp.write("bigger.png", testing::png_claiming(30000, 30000))).find("PNG"), std::string::npos);
    EXPECT_NE(error_of(tmp.write("none.png", testing::png_claiming(0, 5))).find("PNG"), std::string::npos);

    EXPECT_EQ(error_of(tmp.write("empty.png", "")), "image file is empty");
    EXPECT_NE(error_of(tmp.write("anim.png", "GIF89a\x01\x00\x01\x00")).find("unsupported image format: a GIF"),
              std::string::npos);
    EXPECT_NE(error_of(tmp.write("text.png", "hello, world\n")).find("TGA"), std::string::npos);
    EXPECT_NE(error_of(tmp.write("hdr.png", "#?RADIANCE\n")).find("name it .hdr"), std::string::npos);
    EXPECT_EQ(error_of(tmp.path / "missing.png"), "no such file");
    EXPECT_EQ(error_of(tmp.path), "is a folder, not an image");
    EXPECT_NE(error_of(tmp.write("bad.exr", "not an exr")).find("OpenEXR"), std::string::npos);
}

TEST(Texture, AddTextureSharesBySourceAndEncoding) {
    std::vector<Texture> table;
    Texture a = grey(1, 1, {0.5f});
    EXPECT_EQ(add_texture(table, a), 0u);
    EXPECT_EQ(add_texture(table, a), 0u);
    a.encoding = TextureEncoding::Color;
    EXPECT_EQ(add_texture(table, a), 1u);
    a.source = "other";
    EXPECT_EQ(add_texture(table, a), 2u);
    EXPECT_EQ(table.size(), 3u);
}

}  // namespace
}  // namespace sombra
