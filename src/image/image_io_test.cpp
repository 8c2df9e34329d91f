// Encoders, checked by reading the files back with the reference libraries
// (libpng, OpenEXR) or byte by byte (PFM).
#include "image/image_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>
#include <png.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "image/srgb8_table.h"
#include "image/test_folder.h"
#include "image/writers.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;
using test::read_bytes;

constexpr float nan_value = std::numeric_limits<float>::quiet_NaN();
constexpr float inf_value = std::numeric_limits<float>::infinity();

struct PngFile {
    std::uint32_t width = 0, height = 0;
    int bit_depth = 0, colour_type = 0;
    std::vector<std::string> chunks;  // chunk types in file order
    int srgb_intent = -1;
    std::vector<std::uint8_t> rgb;  // decoded by libpng, top row first
};

std::uint32_t big_endian_u32(const std::vector<unsigned char>& bytes, std::size_t at) {
    return (std::uint32_t{bytes[at]} << 24) | (std::uint32_t{bytes[at + 1]} << 16) |
           (std::uint32_t{bytes[at + 2]} << 8) | std::uint32_t{bytes[at + 3]};
}

PngFile read_png(const fs::path& file) {
    PngFile png;
    const std::vector<unsigned char> bytes = read_bytes(file);
    if (bytes.size() < 33) return png;
    png.width = big_endian_u32(bytes, 16);
    png.height = big_endian_u32(bytes, 20);
    png.bit_depth = bytes[24];
    png.colour_type = bytes[25];
    for (std::size_t at = 8; at + 12 <= bytes.size();) {
        const std::uint32_t length = big_endian_u32(bytes, at);
        const std::string type(bytes.begin() + static_cast<long>(at) + 4, bytes.begin() + static_cast<long>(at) + 8);
        if (type == "sRGB") png.srgb_intent = bytes[at + 8];
        png.chunks.push_back(type);
        at += 12 + std::size_t{length};
    }
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, file.c_str())) return png;
    image.format = PNG_FORMAT_RGB;
    png.rgb.resize(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, png.rgb.data(), 0, nullptr)) png.rgb.clear();
    return png;
}

// The 8-bit codes a one-row PNG of these grey values gets, one per pixel.
std::vector<int> png_codes(const fs::path& file, const std::vector<float>& greys, float exposure) {
    std::vector<float> rgb;
    for (float g : greys) rgb.insert(rgb.end(), {g, g, g});
    write_image(file, {static_cast<int>(greys.size()), 1, rgb.data()}, {exposure});
    const PngFile png = read_png(file);
    std::vector<int> codes;
    for (std::size_t i = 0; i + 2 < png.rgb.size(); i += 3) {
        EXPECT_EQ(png.rgb[i], png.rgb[i + 1]);
        EXPECT_EQ(png.rgb[i], png.rgb[i + 2]);
        codes.push_back(png.rgb[i]);
    }
    return codes;
}

using ImageIoTest = test::TestFolder;

TEST(ImageFormat, FollowsTheExtensionInAnyCase) {
    EXPECT_EQ(image_format_for("a.png"), ImageFormat::Png);
    EXPECT_EQ(image_format_for("dir/a.PNG"), ImageFormat::Png);
    EXPECT_EQ(image_format_for("a.pfm"), ImageFormat::Pfm);
    EXPECT_EQ(image_format_for("a.Exr"), ImageFormat::Exr);
    EXPECT_EQ(image_format_for("a.jpg"), ImageFormat::Jpeg);
    EXPECT_EQ(image_format_for("a.JPEG"), ImageFormat::Jpeg);
}

TEST(ImageFormat, UnsupportedExtensionIsNamed) {
    try {
        image_format_for("out/render.tif");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "out/render.tif");
        EXPECT_EQ(e.message(), "unsupported image format 'tif' (use .png, .jpg, .pfm or .exr)");
    }
    EXPECT_THROW(image_format_for("render"), Error);
    EXPECT_THROW(image_format_for("render.png.tmp"), Error);
}

TEST(Srgb, EveryCodeIsTheRoundedExactCurve) {
    // Decoding code k with the exact inverse curve and encoding again gives k,
    // and values just inside a code's half-step boundaries stay on that code.
    for (int k = 0; k < 256; ++k) {
        const double v = k / 255.0;
        const double linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
        EXPECT_EQ(encode_srgb8(static_cast<float>(linear)), k);
    }
    EXPECT_EQ(encode_srgb8(0.0f), 0);
    EXPECT_EQ(encode_srgb8(-0.0f), 0);
    EXPECT_EQ(encode_srgb8(nan_value), 0);
    EXPECT_EQ(encode_srgb8(1.0f), 255);
    EXPECT_EQ(encode_srgb8(inf_value), 255);
}

TEST(Srgb, TheTableGivesEncodeSrgb8sCodes) {
    // Every float within 256 ulps of each of the 255 code boundaries (where
    // a wrong threshold would show), every 97th float of [0, 1.25], and the
    // special values: the table's code is encode_srgb8's.
    const Srgb8Table table;
    auto check = [&](std::uint32_t bits) {
        float f = 0;
        std::memcpy(&f, &bits, sizeof f);
        ASSERT_EQ(table.encode(f), encode_srgb8(f)) << "at " << f;
    };
    for (int k = 1; k < 256; ++k) {
        float lo = 0.0f, hi = 1.0f;  // the boundary by bisection on floats
        for (int i = 0; i < 40; ++i) {
            const float mid = 0.5f * (lo + hi);
            (encode_srgb8(mid) >= k ? hi : lo) = mid;
        }
        std::uint32_t bits = 0;
        std::memcpy(&bits, &hi, sizeof bits);
        for (std::uint32_t b = bits - 256; b <= bits + 256; ++b) check(b);
    }
    for (std::uint32_t b = 0; b <= 0x3fa00000u; b += 97) check(b);
    for (const float f : {0.0f, -0.0f, -1.0f, 1.0f, 2.0f, nan_value, inf_value, -inf_value})
        EXPECT_EQ(table.encode(f), encode_srgb8(f)) << f;
}

TEST_F(ImageIoTest, PngIsEightBitRgbWithAnSrgbChunk) {
    const std::vector<float> rgb(5 * 3 * 3, 0.5f);
    write_image(folder_ / "a.png", {5, 3, rgb.data()}, {});
    const PngFile png = read_png(folder_ / "a.png");
    EXPECT_EQ(png.width, 5u);
    EXPECT_EQ(png.height, 3u);
    EXPECT_EQ(png.bit_depth, 8);
    EXPECT_EQ(png.colour_type, PNG_COLOR_TYPE_RGB);
    EXPECT_EQ(png.srgb_intent, PNG_sRGB_INTENT_PERCEPTUAL);
    ASSERT_FALSE(png.chunks.empty());
    EXPECT_EQ(png.chunks.front(), "IHDR");
    EXPECT_EQ(png.chunks.back(), "IEND");
    const auto before_data = [&](const std::string& type) {
        for (const std::string& chunk : png.chunks) {
            if (chunk == type) return true;
            if (chunk == "IDAT") return false;
        }
        return false;
    };
    EXPECT_TRUE(before_data("sRGB"));
    EXPECT_TRUE(before_data("gAMA"));
    EXPECT_TRUE(before_data("cHRM"));
    EXPECT_EQ(png.rgb, std::vector<std::uint8_t>(5 * 3 * 3, 188));
}

TEST_F(ImageIoTest, PngEncodesTheExactSrgbCurve) {
    // A gamma of 2.2 would give 0, 255, 186, 19, 11, 117, 31.
    EXPECT_EQ(png_codes(folder_ / "a.png", {0.0f, 1.0f, 0.5f, 0.0031308f, 0.001f, 0.18f, 0.01f}, 0.0f),
              (std::vector<int>{0, 255, 188, 10, 3, 118, 25}));
}

TEST_F(ImageIoTest, PngExposureScalesByPowersOfTwo) {
    EXPECT_EQ(png_codes(folder_ / "a.png", {0.25f, 0.09f, 0.5f}, 1.0f), (std::vector<int>{188, 118, 255}));
    EXPECT_EQ(png_codes(folder_ / "b.png", {1.0f, 2.0f, 0.72f}, -2.0f), (std::vector<int>{137, 188, 118}));
}

TEST_F(ImageIoTest, PngClampsOutOfRangeValues) {
    EXPECT_EQ(png_codes(folder_ / "a.png", {-1.0f, -1e-9f, 1.0001f, 2.0f, 1e30f, std::numeric_limits<float>::max()},
                        0.0f),
              (std::vector<int>{0, 0, 255, 255, 255, 255}));
    // A finite value that exposure pushes past float's range is bright, not broken.
    EXPECT_EQ(png_codes(folder_ / "b.png", {1e38f, 1e-38f}, 10.0f), (std::vector<int>{255, 0}));
}

TEST_F(ImageIoTest, PngWritesPixelsWithNonFiniteChannelsAsBlack) {
    const std::vector<float> rgb = {nan_value, 1, 1, 1, inf_value, 1, 1, 1, -inf_value, 1, 0.5f, 0};
    write_image(folder_ / "a.png", {4, 1, rgb.data()}, {});
    EXPECT_EQ(read_png(folder_ / "a.png").rgb, (std::vector<std::uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 188, 0}));
}

TEST_F(ImageIoTest, PngRowsRunTopToBottomAndChannelsStayApart) {
    // Pixel (i, j) = ((i + 1) / 4, (j + 1) / 4, 0.5): every channel differs.
    std::vector<float> rgb;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i)
            rgb.insert(rgb.end(), {static_cast<float>(i + 1) / 4.0f, static_cast<float>(j + 1) / 4.0f, 0.5f});
    write_image(folder_ / "a.png", {3, 2, rgb.data()}, {});
    // sRGB codes of 0.25, 0.5, 0.75 are 137, 188, 225.
    EXPECT_EQ(read_png(folder_ / "a.png").rgb,
              (std::vector<std::uint8_t>{137, 137, 188, 188, 137, 188, 225, 137, 188, 137, 188, 188, 188, 188, 188, 225,
                                         188, 188}));
}

TEST_F(ImageIoTest, PfmBytesAreExact) {
    // 2 x 3 pixels; pixel (i, j) holds (i, j, 0.1 + i + 10 j), plus a negative and a tiny value.
    std::vector<float> rgb;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 2; ++i)
            rgb.insert(rgb.end(),
                       {static_cast<float>(i), static_cast<float>(j), 0.1f + static_cast<float>(i + 10 * j)});
    rgb[0] = -2.5f;
    rgb[1] = 1e-30f;
    write_image(folder_ / "a.pfm", {2, 3, rgb.data()}, {3.0f});  // exposure does not apply

    const std::vector<unsigned char> bytes = read_bytes(folder_ / "a.pfm");
    const std::string header = "PF\n2 3\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 2 * 3 * 3 * 4);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + static_cast<long>(header.size())), header);
    std::size_t at = header.size();
    for (int j = 2; j >= 0; --j) {  // bottom row first
        for (int i = 0; i < 2; ++i) {
            for (int c = 0; c < 3; ++c, at += 4) {
                const std::uint32_t bits = std::uint32_t{bytes[at]} | (std::uint32_t{bytes[at + 1]} << 8) |
                                           (std::uint32_t{bytes[at + 2]} << 16) | (std::uint32_t{bytes[at + 3]} << 24);
                EXPECT_EQ(bits, std::bit_cast<std::uint32_t>(rgb[static_cast<std::size_t>(3 * (j * 2 + i) + c)]))
                    << "pixel " << i << "," << j << " channel " << c;
            }
        }
    }
}

TEST_F(ImageIoTest, PfmWritesPixelsWithNonFiniteChannelsAsZero) {
    const std::vector<float> rgb = {0.25f, nan_value, 3.0f, 7.0f, 8.0f, 9.0f};
    write_image(folder_ / "a.pfm", {2, 1, rgb.data()}, {});
    const std::vector<unsigned char> bytes = read_bytes(folder_ / "a.pfm");
    ASSERT_EQ(bytes.size(), 12u + 24u);
    float values[6];
    std::memcpy(values, bytes.data() + 12, sizeof values);  // the test host is little-endian
    EXPECT_EQ(std::vector<float>(values, values + 6), (std::vector<float>{0, 0, 0, 7, 8, 9}));
}

TEST_F(ImageIoTest, ExrRoundTripGivesTheSameFloats) {
    constexpr int width = 5, height = 3;
    std::vector<float> rgb;
    for (int k = 0; k < width * height * 3; ++k) rgb.push_back(0.1f * static_cast<float>(k) + 1e-7f);
    rgb[3] = 123456.789f;  // beyond half's range
    rgb[4] = 1e-8f;        // below half's precision
    rgb[7] = -0.333333f;
    write_image(folder_ / "a.exr", {width, height, rgb.data()}, {2.0f});  // exposure does not apply

    Imf::InputFile file((folder_ / "a.exr").c_str());
    const Imath::Box2i window = file.header().dataWindow();
    ASSERT_EQ(window.max.x - window.min.x + 1, width);
    ASSERT_EQ(window.max.y - window.min.y + 1, height);
    const Imf::ChannelList& channels = file.header().channels();
    std::vector<float> read(rgb.size(), -1.0f);
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        const Imf::Channel* channel = channels.findChannel(names[c]);
        ASSERT_NE(channel, nullptr);
        EXPECT_EQ(channel->type, Imf::FLOAT);
        char* base = reinterpret_cast<char*>(read.data() + c) -
                     (window.min.x + window.min.y * width) * static_cast<long>(3 * sizeof(float));
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, 3 * sizeof(float), 3 * sizeof(float) * width));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    EXPECT_EQ(read, rgb);
}

TEST_F(ImageIoTest, ExrWritesPixelsWithNonFiniteChannelsAsZero) {
    const std::vector<float> rgb = {inf_value, 2, 3, 4, 5, 6};
    write_image(folder_ / "a.exr", {1, 2, rgb.data()}, {});
    Imf::InputFile file((folder_ / "a.exr").c_str());
    std::vector<float> read(6, -1.0f);
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(read.data() + c), 12, 12));
    file.setFrameBuffer(frame);
    file.readPixels(0, 1);
    EXPECT_EQ(read, (std::vector<float>{0, 0, 0, 4, 5, 6}));
}

}  // namespace
}  // namespace sombra
