// read_hdr_image: EXR and Radiance files written here read back as written;
// every broken file is one Error, never a crash or a huge allocation.
#include "io/images/hdr_image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "image/exr_test_bytes.h"
#include "io/images/exr_test_file.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;
using testing::TempFolder;
using testing::write_exr;

// One pixel in Radiance's RGBE encoding (Ward's float2rgbe).
std::string rgbe(float r, float g, float b) {
    const float m = std::max(r, std::max(g, b));
    if (m < 1e-32f) return std::string(4, '\0');
    int e = 0;
    const float scale = std::frexp(m, &e) * 256.0f / m;
    return {static_cast<char>(static_cast<unsigned char>(r * scale)),
            static_cast<char>(static_cast<unsigned char>(g * scale)),
            static_cast<char>(static_cast<unsigned char>(b * scale)), static_cast<char>(e + 128)};
}

std::string hdr_header(int width, int height) {
    return "#?RADIANCE\n# written by sombra's test\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " +
           std::to_string(width) + "\n";
}

// A Radiance file with flat (unencoded) scanlines.
std::string flat_hdr(int width, int height, const std::vector<float>& rgb) {
    std::string bytes = hdr_header(width, height);
    for (std::size_t p = 0; p < rgb.size() / 3; ++p) bytes += rgbe(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]);
    return bytes;
}

// A Radiance file with "new" run-length encoded scanlines (width 8 … 32767):
// per scanline 2 2 W/256 W%256, then each of the four byte planes as literal runs.
std::string rle_hdr(int width, int height, const std::vector<float>& rgb) {
    std::string bytes = hdr_header(width, height);
    for (int y = 0; y < height; ++y) {
        bytes += {2, 2, static_cast<char>(width >> 8), static_cast<char>(width & 255)};
        std::vector<std::string> pixels;
        for (int x = 0; x < width; ++x) {
            const std::size_t p = 3 * (static_cast<std::size_t>(y) * width + x);
            pixels.push_back(rgbe(rgb[p], rgb[p + 1], rgb[p + 2]));
        }
        for (int plane = 0; plane < 4; ++plane)
            for (int x = 0; x < width; x += 128) {
                const int count = std::min(128, width - x);
                bytes += static_cast<char>(count);
                for (int i = 0; i < count; ++i) bytes += pixels[x + i][plane];
            }
    }
    return bytes;
}

// The message of the Error read_hdr_image throws, "" when it throws none.
std::string error_of(const fs::path& file) {
    try {
        read_hdr_image(file);
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), file.string());
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        return e.message();
    }
    return "";
}

std::vector<float> ramp(int width, int height) {
    std::vector<float> rgb;
    for (int i = 0; i < width * height * 3; ++i)
        rgb.push_back(0.25f * static_cast<float>(i % 7) + 0.125f * static_cast<float>(i % 3));
    return rgb;
}

TEST(HdrImage, ExrReadsBackTheSameFloats) {
    TempFolder folder;
    const std::vector<float> rgb = {0.1f, 2.5f,  1e-6f,  1000.0f, 0.0f,  3.25f, 7.0f, 8.0f, 9.0f,
                                    0.5f, 0.25f, 0.125f, 1e4f,    2e-3f, 0.3f,  4.0f, 5.0f, 6.0f};
    write_exr(folder.path / "a.exr", 3, 2, rgb);
    const HdrImage image = read_hdr_image(folder.path / "a.exr");
    EXPECT_EQ(image.width, 3);
    EXPECT_EQ(image.height, 2);
    EXPECT_EQ(image.rgb, rgb);
}

TEST(HdrImage, ExrDataWindowBecomesTheImage) {
    TempFolder folder;
    const std::vector<float> rgb = ramp(4, 3);
    write_exr(folder.path / "offset.EXR", 4, 3, rgb, {-5, 7});  // extension in any case
    const HdrImage image = read_hdr_image(folder.path / "offset.EXR");
    EXPECT_EQ(image.width, 4);
    EXPECT_EQ(image.height, 3);
    EXPECT_EQ(image.rgb, rgb);
}

TEST(HdrImage, ExrLuminanceOnlyIsGrey) {
    TempFolder folder;
    const std::vector<float> rgb = {0.5f, 0, 0, 2.0f, 0, 0};  // the Y slice reads every third float
    write_exr(folder.path / "y.exr", 2, 1, rgb, {0, 0}, {"Y"});
    const HdrImage image = read_hdr_image(folder.path / "y.exr");
    EXPECT_EQ(image.rgb, (std::vector<float>{0.5f, 0.5f, 0.5f, 2.0f, 2.0f, 2.0f}));
}

TEST(HdrImage, ExrMissingChannelReadsAsZero) {
    TempFolder folder;
    const std::vector<float> rgb = {0.5f, 1.5f, 9.0f};
    write_exr(folder.path / "rg.exr", 1, 1, rgb, {0, 0}, {"R", "G"});
    EXPECT_EQ(read_hdr_image(folder.path / "rg.exr").rgb, (std::vector<float>{0.5f, 1.5f, 0.0f}));
}

// Tiled files (textures are often tiled and mip-mapped) read as their first level.
TEST(HdrImage, ExrTiledFilesReadTheirFirstLevel) {
    TempFolder folder;
    const std::vector<float> rgb = ramp(11, 7);
    for (const Imf::LevelMode mode : {Imf::ONE_LEVEL, Imf::MIPMAP_LEVELS, Imf::RIPMAP_LEVELS})
        for (const Imf::LevelRoundingMode rounding : {Imf::ROUND_DOWN, Imf::ROUND_UP})
            for (const Imf::Compression compression :
                 {Imf::NO_COMPRESSION, Imf::ZIP_COMPRESSION, Imf::PIZ_COMPRESSION}) {
                SCOPED_TRACE(std::to_string(mode) + " " + std::to_string(rounding) + " " + std::to_string(compression));
                test::write_tiled_exr(folder.path / "tiled.exr", 11, 7, rgb, Imf::TileDescription(4, 3, mode, rounding),
                                      compression);
                const HdrImage image = read_hdr_image(folder.path / "tiled.exr");
                EXPECT_EQ(image.width, 11);
                EXPECT_EQ(image.height, 7);
                EXPECT_EQ(image.rgb, rgb);
            }
}

TEST(HdrImage, RadianceFlatAndRunLengthReadBack) {
    TempFolder folder;
    for (const int width : {3, 10, 200}) {
        const int height = 2;
        const std::vector<float> rgb = ramp(width, height);
        const std::string bytes = width < 8 ? flat_hdr(width, height, rgb) : rle_hdr(width, height, rgb);
        const fs::path file = folder.write("width" + std::to_string(width) + ".hdr", bytes);
        const HdrImage image = read_hdr_image(file);
        ASSERT_EQ(image.width, width);
        ASSERT_EQ(image.height, height);
        ASSERT_EQ(image.rgb.size(), rgb.size());
        for (std::size_t i = 0; i < rgb.size(); i += 3) {
            const float m = std::max(rgb[i], std::max(rgb[i + 1], rgb[i + 2]));
            for (std::size_t c = 0; c < 3; ++c)  // RGBE keeps 8 bits relative to the largest component
                EXPECT_NEAR(image.rgb[i + c], rgb[i + c], m / 128.0f) << "width " << width << " float " << i + c;
        }
    }
}

TEST(HdrImage, MissingFileAndWrongExtension) {
    TempFolder folder;
    EXPECT_EQ(error_of(folder.path / "nothing.exr"), "no such file");
    EXPECT_EQ(error_of(folder.path / "nothing.hdr"), "no such file");
    const fs::path png = folder.write("sky.png", "not really");
    EXPECT_EQ(error_of(png), "unsupported image format \".png\" (supported: .exr (OpenEXR), .hdr (Radiance))");
    const fs::path none = folder.write("sky", "no extension");
    EXPECT_NE(error_of(none).find("supported: .exr"), std::string::npos);
}

TEST(HdrImage, GarbageAndTruncatedFiles) {
    TempFolder folder;
    EXPECT_NE(
        error_of(folder.write("garbage.exr", "this is not an OpenEXR file at all")).find("cannot read as OpenEXR"),
        std::string::npos);
    EXPECT_NE(error_of(folder.write("empty.exr", "")), "");
    EXPECT_NE(error_of(folder.write("garbage.hdr", "hello")).find("not a Radiance HDR file"), std::string::npos);
    EXPECT_NE(error_of(folder.write("empty.hdr", "")), "");
    EXPECT_NE(error_of(folder.write("noformat.hdr", "#?RADIANCE\n\n-Y 1 +X 1\nabcd")), "");
    EXPECT_NE(error_of(folder.write("layout.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 1 -X 1\nabcd")), "");
    EXPECT_NE(error_of(folder.write("zero.hdr", hdr_header(0, 0))).find("no pixels"), std::string::npos);

    // Every cut of a valid file, header or pixels, is an error. (Debian's stb
    // used to loop forever on the run-length files cut in their pixels.)
    const std::vector<float> rgb = ramp(3, 2);
    const std::string flat = flat_hdr(3, 2, rgb);
    const std::string rle = rle_hdr(10, 2, ramp(10, 2));
    for (const std::string* whole : {&flat, &rle})
        for (std::size_t cut = 0; cut < whole->size(); ++cut)
            EXPECT_NE(error_of(folder.write("cut.hdr", whole->substr(0, cut))), "") << "cut at " << cut;

    write_exr(folder.path / "whole.exr", 3, 2, rgb);
    std::ifstream in(folder.path / "whole.exr", std::ios::binary);
    const std::string exr((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (std::size_t cut = 0; cut < exr.size(); cut += 7)
        EXPECT_NE(error_of(folder.write("cut.exr", exr.substr(0, cut))), "") << "cut at " << cut;
}

// Textures and environment maps go through the layout check shards do
// (image/exr_check.h): a chunk claiming 2 GiB is refused before OpenEXR reads it.
TEST(HdrImage, ExrLayoutIsCheckedBeforeOpenExrReadsIt) {
    TempFolder folder;
    write_exr(folder.path / "sky.exr", 3, 2, ramp(3, 2));
    std::ifstream in(folder.path / "sky.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t chunk = test::exr_chunk(bytes, 0);
    test::put_le(bytes, chunk + 4, 4, 0x7fffffffu);
    EXPECT_EQ(error_of(folder.write("claims.exr", bytes)),
              "damaged EXR file: pixel chunk 0 claims 2147483647 bytes, more than the " +
                  std::to_string(bytes.size() - chunk - 8) + " left in the file");
}

TEST(HdrImage, NegativeNanAndInfinitePixelsNameThePixel) {
    TempFolder folder;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    struct Case {
        float bad;
        const char* what;
    };
    for (const Case& c :
         {Case{-0.5f, "negative (-0.5)"}, Case{nan, "NaN"}, Case{inf, "infinite"}, Case{-inf, "infinite"}}) {
        std::vector<float> rgb(3 * 4 * 3, 1.0f);
        rgb[3 * (2 * 4 + 1) + 2] = c.bad;  // pixel (1, 2), blue
        rgb[3 * (2 * 4 + 3) + 0] = -1.0f;  // a later one, not named
        write_exr(folder.path / "bad.exr", 4, 3, rgb);
        EXPECT_EQ(error_of(folder.path / "bad.exr"), std::string("pixel (1, 2) is ") + c.what);
    }
}

TEST(HdrImage, NegativeHintIsAppended) {
    TempFolder folder;
    std::vector<float> rgb(3 * 2 * 2, 1.0f);
    rgb[3 * 1 + 0] = -2.0f;  // pixel (1, 0), red
    write_exr(folder.path / "neg.exr", 2, 2, rgb);
    try {
        read_hdr_image(folder.path / "neg.exr", HdrReadOptions{false, "; try X"});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.message(), "pixel (1, 0) is negative (-2); try X");
    }
}

TEST(HdrImage, ClampNegativeReadsNegativesAsZeroAndCountsThem) {
    TempFolder folder;
    std::vector<float> rgb(3 * 3 * 2, 0.5f);
    rgb[0] = -1.0f;
    rgb[3 * 4 + 2] = -0.25f;
    rgb[3 * 5 + 1] = -99.7f;
    write_exr(folder.path / "neg.exr", 3, 2, rgb);
    std::size_t clamped = 1234;
    const HdrImage image = read_hdr_image(folder.path / "neg.exr", HdrReadOptions{true, {}}, &clamped);
    EXPECT_EQ(clamped, 3u);
    ASSERT_EQ(image.rgb.size(), rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_EQ(image.rgb[i], rgb[i] < 0 ? 0.0f : rgb[i]) << i;

    // Nothing to clamp: the count is 0.
    write_exr(folder.path / "ok.exr", 1, 1, {1, 2, 3});
    read_hdr_image(folder.path / "ok.exr", HdrReadOptions{true, {}}, &clamped);
    EXPECT_EQ(clamped, 0u);
}

TEST(HdrImage, ClampNegativeKeepsNanAndInfinityErrors) {
    TempFolder folder;
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        std::vector<float> rgb(3 * 2, -1.0f);
        rgb[4] = bad;  // pixel (1, 0), green
        write_exr(folder.path / "bad.exr", 2, 1, rgb);
        try {
            read_hdr_image(folder.path / "bad.exr", HdrReadOptions{true, {}});
            FAIL() << "expected an error for " << bad;
        } catch (const Error& e) {
            EXPECT_EQ(e.message().rfind("pixel (1, 0) is ", 0), 0u) << e.message();
            EXPECT_EQ(e.message().find("negative"), std::string::npos) << e.message();
        }
    }
}

TEST(HdrImage, HugeSizeIsRefusedFromTheHeader) {
    TempFolder folder;
    const auto start = std::chrono::steady_clock::now();
    const fs::path hdr = folder.write("huge.hdr", hdr_header(100000, 100000) + std::string(64, '\x01'));
    EXPECT_NE(error_of(hdr).find("more than the limit of 32768 per side"), std::string::npos) << error_of(hdr);
    const fs::path wide = folder.write("wide.hdr", hdr_header(40000, 1) + std::string(64, '\x01'));
    EXPECT_NE(error_of(wide).find("more than the limit"), std::string::npos);
    const fs::path many = folder.write("many.hdr", hdr_header(30000, 30000) + std::string(64, '\x01'));
    EXPECT_NE(error_of(many).find("more than the limit"), std::string::npos);

    // An EXR header claiming 100000 × 100000 pixels (the pixels were never written).
    {
        Imf::Header header(100000, 100000);
        header.channels().insert("R", Imf::Channel(Imf::FLOAT));
        Imf::OutputFile out((folder.path / "huge.exr").c_str(), header);
    }
    EXPECT_NE(error_of(folder.path / "huge.exr").find("more than the limit"), std::string::npos)
        << error_of(folder.path / "huge.exr");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

// The shared maps either load with every pixel finite and non-negative, or
// are refused naming a pixel that really is negative. (When this was written, all four
// of shared/envmaps hold negative pixels, up to −149 in studio.exr: ringing
// from the resampling that made them. Spec §10 makes such a map an error.)
TEST(HdrImage, SharedEnvironmentMaps) {
    const fs::path folder = fs::path(SOMBRA_SHARED_DIR) / "envmaps";
    for (const char* name : {"sunset.exr", "studio.exr", "forest.exr", "city.exr"}) {
        const fs::path file = folder / name;
        if (!fs::exists(file)) GTEST_SKIP() << file << " is missing (shared/envmaps not found)";
        HdrImage image;
        try {
            image = read_hdr_image(file);
        } catch (const Error& e) {
            int x = -1, y = -1;
            ASSERT_EQ(std::sscanf(e.message().c_str(), "pixel (%d, %d) is negative", &x, &y), 2) << e.what();
            Imf::InputFile raw(file.c_str());
            const Imath::Box2i window = raw.header().dataWindow();
            const int width = window.max.x - window.min.x + 1;
            std::vector<float> rgb(static_cast<std::size_t>(width) * (window.max.y - window.min.y + 1) * 3);
            Imf::FrameBuffer frame;
            const char* names[3] = {"R", "G", "B"};
            for (std::size_t c = 0; c < 3; ++c)
                frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, window, 12,
                                                        12 * static_cast<std::size_t>(width)));
            raw.setFrameBuffer(frame);
            raw.readPixels(window.min.y, window.max.y);
            const float* p = &rgb[3 * (static_cast<std::size_t>(y) * width + x)];
            EXPECT_LT(std::min(p[0], std::min(p[1], p[2])), 0.0f) << name;
            std::cout << "note: " << e.what() << " (spec §10: a map with a negative pixel is an error)\n";
            continue;
        }
        EXPECT_EQ(image.width, 2 * image.height) << name << " is equirectangular";
        ASSERT_EQ(image.rgb.size(), static_cast<std::size_t>(image.width) * image.height * 3);
        for (const float v : image.rgb) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
    }
}

}  // namespace
}  // namespace sombra
