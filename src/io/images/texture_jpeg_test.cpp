// JPEG textures through libjpeg-turbo: files written here with libjpeg
// itself (baseline, progressive, grey, CMYK, custom scan scripts) decode to
// the pixels their coefficients hold, and files whose data would give wrong
// pixels are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
// jpeglib.h uses size_t and FILE without including their headers.
#include <jpeglib.h>

#include "core/error.h"
#include "io/images/texture_image.h"
#include "io/images/texture_jpeg.h"
#include "scene/texture.h"

namespace sombra {
namespace {

struct JpegFile {
    int width = 0, height = 0;
    int components = 3;  // 1 grey, 3 RGB, 4 CMYK
    bool progressive = false;
    std::vector<jpeg_scan_info> scans{};  // a custom scan script when not empty
};

// libjpeg's own encoder, into memory, standard Huffman tables (no
// optimisation) and quality 95. Test data only: a failure aborts.
std::vector<unsigned char> encode(const JpegFile& file, const std::vector<unsigned char>& values) {
    jpeg_compress_struct info{};
    jpeg_error_mgr errors{};
    info.err = jpeg_std_error(&errors);
    jpeg_create_compress(&info);
    unsigned char* buffer = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&info, &buffer, &size);
    info.image_width = static_cast<JDIMENSION>(file.width);
    info.image_height = static_cast<JDIMENSION>(file.height);
    info.input_components = file.components;
    info.in_color_space = file.components == 1 ? JCS_GRAYSCALE : file.components == 3 ? JCS_RGB : JCS_CMYK;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, 95, TRUE);
    if (file.progressive) jpeg_simple_progression(&info);
    if (!file.scans.empty()) {
        info.scan_info = file.scans.data();
        info.num_scans = static_cast<int>(file.scans.size());
    }
    jpeg_start_compress(&info, TRUE);
    const auto stride = static_cast<std::size_t>(file.width) * static_cast<std::size_t>(file.components);
    while (info.next_scanline < info.image_height) {
        auto* row = const_cast<JSAMPLE*>(values.data() + stride * info.next_scanline);
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    std::vector<unsigned char> bytes(buffer, buffer + size);
    std::free(buffer);
    return bytes;
}

// A smooth image (JPEG keeps it within a code or two) of width × height × channels.
std::vector<unsigned char> gradient(int width, int height, int channels) {
    std::vector<unsigned char> v;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c)
                v.push_back(static_cast<unsigned char>(40 + (150 * x) / width + (50 * y) / height + 20 * c));
    return v;
}

Texture decode(const std::vector<unsigned char>& bytes) {
    return decode_texture(bytes, TextureEncoding::Data, "t.jpg");
}

std::string refusal(const std::vector<unsigned char>& bytes) {
    try {
        decode(bytes);
    } catch (const Error& e) {
        return e.what();
    }
    return "decoded";
}

double mean_code_error(const Texture& t, const std::vector<unsigned char>& values) {
    double sum = 0;
    for (std::size_t i = 0; i < values.size(); ++i) sum += std::abs(t.texels[i] * 255.0 - values[i]);
    return sum / static_cast<double>(values.size());
}

// Where the bytes `marker` (0xff, code) first occur at or after `from`.
std::size_t find_marker(const std::vector<unsigned char>& bytes, unsigned char code, std::size_t from = 0) {
    for (std::size_t i = from; i + 1 < bytes.size(); ++i)
        if (bytes[i] == 0xff && bytes[i + 1] == code) return i;
    return bytes.size();
}

TEST(JpegTexture, ProgressiveAndBaselineDecodeToTheSamePixels) {
    // 40 × 24: neither side a multiple of the 16-pixel chroma MCU.
    JpegFile file{40, 24, 3};
    const std::vector<unsigned char> values = gradient(40, 24, 3);
    const Texture baseline = decode(encode(file, values));
    file.progressive = true;
    const Texture progressive = decode(encode(file, values));
    ASSERT_EQ(baseline.width, 40);
    ASSERT_EQ(baseline.height, 24);
    ASSERT_EQ(baseline.channels, 3);
    // The same quantised coefficients, only sent in another order.
    EXPECT_EQ(progressive.texels, baseline.texels);
    EXPECT_LT(mean_code_error(baseline, values), 2.0);
}

TEST(JpegTexture, GreyStaysOneChannel) {
    const std::vector<unsigned char> values = gradient(17, 9, 1);
    const Texture t = decode(encode({17, 9, 1}, values));
    ASSERT_EQ(t.channels, 1);
    ASSERT_EQ(t.texels.size(), values.size());
    EXPECT_LT(mean_code_error(t, values), 2.0);
}

TEST(JpegTexture, AdobeCmykIsInvertedInksTimesBlack) {
    // libjpeg writes Adobe's marker for CMYK; the stored values are taken as
    // Photoshop's inverted inks: R = C·K/255, G = M·K/255, B = Y·K/255.
    std::vector<unsigned char> cmyk;
    for (int i = 0; i < 16 * 16; ++i) cmyk.insert(cmyk.end(), {200, 100, 50, 128});
    const Texture t = decode(encode({16, 16, 4}, cmyk));
    ASSERT_EQ(t.channels, 3);
    const double expected[3] = {200 * 128 / 255.0, 100 * 128 / 255.0, 50 * 128 / 255.0};
    for (std::size_t i = 0; i < t.texels.size(); ++i) EXPECT_NEAR(t.texels[i] * 255.0, expected[i % 3], 2.0) << i;
}

// fuzz_texture found that stb_image decoded a scan whose Huffman tables the
// file never defines from uninitialised memory. libjpeg takes the standard
// tables then (Motion JPEG leaves them out), which is what libjpeg's encoder
// wrote: the file without its tables decodes to the very same pixels.
TEST(JpegTexture, ScanWithoutHuffmanTablesUsesTheStandardOnes) {
    const std::vector<unsigned char> values = gradient(24, 16, 3);
    const std::vector<unsigned char> bytes = encode({24, 16, 3}, values);
    std::vector<unsigned char> stripped;
    for (std::size_t at = 0; at < bytes.size();) {
        const std::size_t dht = find_marker(bytes, 0xc4, at);
        stripped.insert(stripped.end(), bytes.begin() + static_cast<long>(at), bytes.begin() + static_cast<long>(dht));
        if (dht == bytes.size()) break;
        at = dht + 2 + ((std::size_t{bytes[dht + 2]} << 8) | bytes[dht + 3]);
    }
    ASSERT_LT(stripped.size() + 400, bytes.size()) << "the tables were not taken out";
    EXPECT_EQ(decode(stripped).texels, decode(bytes).texels);
}

TEST(JpegTexture, CorruptTruncatedAndImagelessFilesAreRefused) {
    const std::vector<unsigned char> bytes = encode({32, 32, 3}, gradient(32, 32, 3));
    // Sixteen 1 bits (0xff stuffed as ff 00) are no code of the standard tables.
    std::vector<unsigned char> corrupt = bytes;
    const std::size_t scan = find_marker(corrupt, 0xda);
    const std::size_t data = scan + 2 + ((std::size_t{corrupt[scan + 2]} << 8) | corrupt[scan + 3]);
    for (std::size_t i = 0; i < 8; i += 2) {
        corrupt[data + i] = 0xff;
        corrupt[data + i + 1] = 0x00;
    }
    EXPECT_EQ(refusal(corrupt), "t.jpg: cannot decode as JPEG: Corrupt JPEG data: bad Huffman code");

    const std::vector<unsigned char> half(bytes.begin(), bytes.begin() + static_cast<long>(bytes.size() / 2));
    EXPECT_EQ(refusal(half), "t.jpg: JPEG file is truncated");
    // Cut anywhere, even just before its end-of-image marker.
    const std::vector<unsigned char> no_end(bytes.begin(), bytes.end() - 2);
    EXPECT_EQ(refusal(no_end), "t.jpg: JPEG file is truncated");

    // Start of image, then straight to the end: tables only (an "abbreviated" file).
    EXPECT_EQ(refusal({0xff, 0xd8, 0xff, 0xd9}), "t.jpg: cannot decode as JPEG: JPEG datastream contains no image");
    // 0xff fill bytes before the start of image are skipped.
    std::vector<unsigned char> filled{0xff, 0xff, 0xff};
    filled.insert(filled.end(), bytes.begin(), bytes.end());
    EXPECT_EQ(decode(filled).texels, decode(bytes).texels);
}

// One scan per AC coefficient and bit: the DC, then each of the 63 AC
// coefficients first at point transform `first_bit`, then refined bit by bit.
std::vector<jpeg_scan_info> scan_per_coefficient_and_bit(int first_bit) {
    std::vector<jpeg_scan_info> scans{{1, {0, 0, 0, 0}, 0, 0, 0, 0}};
    for (int k = 1; k < 64; ++k) {
        scans.push_back({1, {0, 0, 0, 0}, k, k, 0, first_bit});
        for (int bit = first_bit; bit > 0; --bit) scans.push_back({1, {0, 0, 0, 0}, k, k, bit, bit - 1});
    }
    return scans;
}

TEST(JpegTexture, ProgressiveFilesOfMoreThanTheScanLimitAreRefused) {
    const std::vector<unsigned char> values = gradient(8, 8, 1);
    JpegFile file{8, 8, 1};
    file.scans = scan_per_coefficient_and_bit(0);  // 64 scans: a valid, if odd, file
    const Texture t = decode(encode(file, values));
    EXPECT_LT(mean_code_error(t, values), 2.0);

    file.scans = scan_per_coefficient_and_bit(4);  // 1 + 63 × 5 = 316 scans
    ASSERT_GT(static_cast<int>(file.scans.size()), kMaxJpegScans);
    EXPECT_EQ(refusal(encode(file, values)),
              "t.jpg: cannot decode as JPEG: more than " + std::to_string(kMaxJpegScans) + " scans");
}

}  // namespace
}  // namespace sombra
