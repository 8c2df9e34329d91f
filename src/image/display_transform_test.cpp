// 8-bit outputs (spec §27): Khronos PBR Neutral against values worked by
// hand from its specification, and JPEG files read back by libjpeg.
#include "image/display_transform.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <vector>
// jpeglib.h uses size_t and FILE without including their headers.
#include <jpeglib.h>

#include "core/error.h"
#include "image/test_folder.h"
#include "image/writers.h"

namespace sombra {
namespace {

void expect_near(Vec3 got, Vec3 want, float tolerance = 2e-6f) {
    EXPECT_NEAR(got.x, want.x, tolerance);
    EXPECT_NEAR(got.y, want.y, tolerance);
    EXPECT_NEAR(got.z, want.z, tolerance);
}

TEST(PbrNeutral, KeepsBaseColoursAndCompressesHighlightsAsTheSpecificationSays) {
    // Below the compression's start only the offset applies: 0.04 once the
    // smallest channel reaches 0.08, x − 6.25x² under it.
    expect_near(pbr_neutral({0.5f, 0.5f, 0.5f}), {0.46f, 0.46f, 0.46f});
    expect_near(pbr_neutral({0.6f, 0.3f, 0.04f}), {0.6f - 0.03f, 0.3f - 0.03f, 0.04f - 0.03f});
    expect_near(pbr_neutral(Vec3{0.0f}), Vec3{0.0f});
    // (2, 1, 0.5): offset 0.04, peak 1.96, new peak 1 − 0.24²/1.44 = 0.96,
    // scaled by 0.96/1.96, then 1 − 1/1.15 of the way to grey 0.96.
    const double g = 1.0 - 1.0 / 1.15, s = 0.96 / 1.96;
    expect_near(pbr_neutral({2.0f, 1.0f, 0.5f}), {0.96f, static_cast<float>(0.96 * s * (1 - g) + 0.96 * g),
                                                  static_cast<float>(0.46 * s * (1 - g) + 0.96 * g)});
}

TEST(PbrNeutral, GreysRiseSteadilyTowardWhiteWithoutReachingIt) {
    float previous = -1.0f;
    for (float v = 0.0f; v < 1000.0f; v = v * 1.05f + 0.001f) {
        const Vec3 t = pbr_neutral(Vec3{v});
        EXPECT_EQ(t.x, t.y);
        EXPECT_EQ(t.y, t.z);
        EXPECT_GE(t.x, previous) << v;
        EXPECT_LT(t.x, 1.0f) << v;
        previous = t.x;
    }
    EXPECT_GT(previous, 0.999f);
    // Continuous where compression starts (peak 0.76 after the offset).
    EXPECT_NEAR(pbr_neutral(Vec3{0.8f - 1e-5f}).x, pbr_neutral(Vec3{0.8f + 1e-5f}).x, 1e-4f);
}

TEST(PbrNeutral, NamesAreTheCommandLines) {
    EXPECT_EQ(tonemap_option("none"), Tonemap::None);
    EXPECT_EQ(tonemap_option("pbr-neutral"), Tonemap::PbrNeutral);
    EXPECT_EQ(tonemap_name(Tonemap::PbrNeutral), "pbr-neutral");
    try {
        tonemap_option("aces");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "--tonemap");
        EXPECT_EQ(e.message(), "expected none or pbr-neutral, not 'aces'");
    }
}

TEST(DisplayBytes, TheToneMapperActsAfterTheExposureAndBeforeSrgb) {
    const std::vector<float> rgb{1.0f, 0.5f, 0.25f};
    const std::vector<std::uint8_t> bytes = display_bytes({1, 1, rgb.data()}, {1.0f, Tonemap::PbrNeutral});
    const Vec3 mapped = pbr_neutral({2.0f, 1.0f, 0.5f});
    EXPECT_EQ(bytes,
              (std::vector<std::uint8_t>{encode_srgb8(mapped.x), encode_srgb8(mapped.y), encode_srgb8(mapped.z)}));
}

// A JPEG file decoded by libjpeg: width, height, RGB bytes.
struct JpegImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
};

JpegImage read_jpeg(const std::filesystem::path& path) {
    JpegImage image;
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) return image;
    jpeg_decompress_struct info{};
    jpeg_error_mgr errors{};
    info.err = jpeg_std_error(&errors);  // a bad file exits the test: fine here
    jpeg_create_decompress(&info);
    jpeg_stdio_src(&info, file);
    jpeg_read_header(&info, TRUE);
    info.out_color_space = JCS_RGB;
    jpeg_start_decompress(&info);
    image.width = static_cast<int>(info.output_width);
    image.height = static_cast<int>(info.output_height);
    image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = image.rgb.data() + static_cast<std::size_t>(info.output_scanline) * image.width * 3;
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    std::fclose(file);
    return image;
}

using JpegTest = test::TestFolder;

TEST_F(JpegTest, AJpegHoldsTheSrgbCodesOfItsPixelsWithinItsQuantisation) {
    // Four 16 × 16 flat squares: JPEG's 8 × 8 blocks stay flat inside each.
    constexpr int side = 32;
    const Vec3 colours[4] = {{0.5f, 0.5f, 0.5f}, {0.8f, 0.1f, 0.05f}, {0.02f, 0.3f, 0.9f}, {3.0f, 2.0f, 1.0f}};
    std::vector<float> rgb;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const Vec3 c = colours[(y / 16) * 2 + x / 16];
            rgb.insert(rgb.end(), {c.x, c.y, c.z});
        }
    for (const Tonemap tonemap : {Tonemap::None, Tonemap::PbrNeutral}) {
        const std::filesystem::path path = folder_ / "a.jpg";
        write_image(path, {side, side, rgb.data()}, {0.0f, tonemap});
        const JpegImage jpeg = read_jpeg(path);
        ASSERT_EQ(jpeg.width, side);
        ASSERT_EQ(jpeg.height, side);
        const std::vector<std::uint8_t> want = display_bytes({side, side, rgb.data()}, {0.0f, tonemap});
        // Centres of the squares, away from the chroma subsampling's edges.
        for (const int pixel : {4 * side + 4, 4 * side + 20, 20 * side + 4, 20 * side + 20})
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(jpeg.rgb[3 * pixel + c], want[3 * pixel + c], 4) << pixel << " " << c;
    }
}

TEST_F(JpegTest, AnImageWiderThanAJpegHoldsIsOneError) {
    const std::vector<float> rgb(3 * 65501, 0.5f);
    try {
        write_image(folder_ / "wide.jpg", {65501, 1, rgb.data()}, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.message(), "a JPEG holds at most 65500 pixels a side, not 65501x1");
        EXPECT_EQ(e.where(), (folder_ / "wide.jpg").string());
    }
    EXPECT_TRUE(entries().empty());
}

}  // namespace
}  // namespace sombra
