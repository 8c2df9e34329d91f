// read_exr_channels (image_io.h) on files sombra's writer made, as written
// and with their line-offset table, chunk sizes or header patched to claim
// what they do not hold: each patch is one Error naming what is wrong, found
// before OpenEXR allocates anything for it (exr_check.h).
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "image/exr_test_bytes.h"
#include "image/image_io.h"
#include "image/test_folder.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;
using test::get_le;
using test::put_le;

constexpr int kWidth = 71, kHeight = 49;  // 4 chunks of 16 rows (ZIP), the last of 1

class ExrReader : public test::TestFolder {
protected:
    // A shard-like file: R, G, B and a depth layer, two text attributes.
    void SetUp() override {
        TestFolder::SetUp();
        for (int k = 0; k < kWidth * kHeight; ++k) {
            rgb_.insert(rgb_.end(), {0.01f * static_cast<float>(k % 97), 0.5f, static_cast<float>(k) * 1e-3f});
            depth_.push_back(static_cast<float>(k % 13) + 0.25f);
        }
        const ImageChannel layers[] = {{"depth.Z", depth_.data(), 1}};
        const ImageAttribute attributes[] = {{"sombra.shard", "0/1"}, {"sombra.render", "test"}};
        write_image(folder_ / "good.exr", {kWidth, kHeight, rgb_.data()}, {}, layers, attributes);
        good_ = test::read_bytes(folder_ / "good.exr");
        table_ = test::exr_header_end(good_);
    }
    std::size_t chunk(int k) const { return get_le(good_, table_ + 8 * static_cast<std::size_t>(k), 8); }

    // Writes `bytes` as a file and expects read_exr_channels to refuse it with `message`.
    void expect_refused(const Bytes& bytes, const std::string& message) {
        const fs::path file = folder_ / "bad.exr";
        std::ofstream(file, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        try {
            read_exr_channels(file);
            ADD_FAILURE() << "read: expected '" << message << "'";
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), file.string());
            EXPECT_NE(e.message().find(message), std::string::npos) << e.message();
            EXPECT_EQ(e.message().find('\n'), std::string::npos) << e.message();
        }
    }

    std::vector<float> rgb_, depth_;
    Bytes good_;
    std::size_t table_ = 0;
};

TEST_F(ExrReader, ReadsWhatTheWriterWroteChunkByChunk) {
    const ExrChannels exr = read_exr_channels(folder_ / "good.exr");
    ASSERT_EQ(exr.width, kWidth);
    ASSERT_EQ(exr.height, kHeight);
    ASSERT_EQ(exr.names, (std::vector<std::string>{"B", "G", "R", "depth.Z"}));
    for (std::size_t k = 0; k < rgb_.size() / 3; ++k) {
        ASSERT_EQ(exr.values[2][k], rgb_[3 * k]) << k;
        ASSERT_EQ(exr.values[0][k], rgb_[3 * k + 2]) << k;
        ASSERT_EQ(exr.values[3][k], depth_[k]) << k;
    }
    for (const auto& channel : exr.values) EXPECT_EQ(channel.capacity(), channel.size());
    EXPECT_EQ(chunk(0), table_ + 8 * 4);  // the layout the patches below assume
}

TEST_F(ExrReader, RefusesChunkSizesPastTheFileOrTheirRows) {
    const std::size_t size_at = chunk(0) + 4;
    Bytes bytes = good_;
    put_le(bytes, size_at, 4, 0x7fffffffu);  // 2 GiB
    expect_refused(bytes, "damaged EXR file: pixel chunk 0 claims 2147483647 bytes, more than the " +
                              std::to_string(good_.size() - chunk(0) - 8) + " left in the file");
    bytes = good_;
    put_le(bytes, size_at, 4, 0xffffffffu);
    expect_refused(bytes, "pixel chunk 0 claims a negative size (-1 bytes)");
    // Inside the file (padded with 4 MiB), but more than 16 rows of 71 pixels of 4 floats.
    bytes = good_;
    bytes.resize(bytes.size() + (4u << 20), 0);
    put_le(bytes, size_at, 4, 1u << 20);
    expect_refused(bytes, "pixel chunk 0 claims 1048576 bytes, more than its 16 rows hold uncompressed (18176)");
    // The last chunk (one row) too.
    bytes = good_;
    bytes.resize(bytes.size() + 4096, 0);
    put_le(bytes, chunk(3) + 4, 4, 1200);
    expect_refused(bytes, "pixel chunk 3 claims 1200 bytes, more than its 1 rows hold uncompressed (1136)");
    // Within its rows and the file, but over the next chunk.
    bytes = good_;
    put_le(bytes, size_at, 4, get_le(bytes, size_at, 4) + 1);
    expect_refused(bytes, "the pixel chunks at bytes " + std::to_string(chunk(0)) + " and " + std::to_string(chunk(1)) +
                              " overlap");
}

TEST_F(ExrReader, RefusesOffsetsOutsideThePixelDataOrAtAnotherChunk) {
    for (const std::uint64_t offset : {std::uint64_t{1} << 40, std::uint64_t{good_.size() - 7}, std::uint64_t{0},
                                       std::uint64_t{8}, std::uint64_t{table_ + 8}}) {
        Bytes bytes = good_;
        put_le(bytes, table_ + 8, 8, offset);
        expect_refused(bytes, "damaged EXR file: pixel chunk 1 is at byte " + std::to_string(offset) +
                                  ", outside the pixel data (bytes " + std::to_string(table_ + 32) + " to " +
                                  std::to_string(good_.size()) + ")");
    }
    Bytes bytes = good_;
    put_le(bytes, table_ + 8, 8, chunk(0));  // chunk 0 twice
    expect_refused(bytes, "pixel chunk 1 starts at row 0, not 16");
    expect_refused(Bytes(good_.begin(), good_.begin() + static_cast<std::ptrdiff_t>(table_ + 20)),
                   "its line-offset table of 4 entries is cut short");
}

TEST_F(ExrReader, RefusesTiledMultipartDeepAndBadHeaders) {
    Bytes bytes = good_;
    bytes[5] |= 0x02;  // version flags: single-part tiled, but the header says nothing of tiles
    expect_refused(bytes, "no 'tiles' attribute in a tiled file");
    for (const int flag : {0x08, 0x10}) {  // non-image (deep), multi-part
        bytes = good_;
        bytes[5] = static_cast<unsigned char>(bytes[5] | flag);
        expect_refused(bytes, "not a single-part flat EXR file");
    }
    const auto attribute = [&](const std::string& name) {  // where its type starts
        const char* text = name.c_str();
        const auto at = std::search(good_.begin(), good_.end(), text, text + name.size() + 1) - good_.begin();
        return static_cast<std::size_t>(at) + name.size() + 1;
    };
    bytes = good_;
    const std::size_t compression = attribute("compression") + 12 + 4;
    ASSERT_EQ(bytes[compression], 3);  // ZIP
    bytes[compression] = 10;
    expect_refused(bytes, "an EXR file of unknown compression 10");
    // A float claiming 5 bytes would make OpenEXR read the rest of the header askew.
    bytes = good_;
    const std::size_t aspect = attribute("pixelAspectRatio") + 6;
    ASSERT_EQ(get_le(bytes, aspect, 4), 4u);
    put_le(bytes, aspect, 4, 5);
    expect_refused(bytes, "attribute 'pixelAspectRatio' of type float has 5 bytes");
    bytes = good_;
    const std::size_t channels = attribute("channels") + 7;
    put_le(bytes, channels, 4, get_le(bytes, channels, 4) + 1);  // one byte past its end
    expect_refused(bytes, "attribute 'channels' of type chlist has");
    bytes = good_;
    put_le(bytes, channels + 4 + 2, 4, 7);  // the first channel's ("B") pixel type
    expect_refused(bytes, "EXR channel 'B' has an unknown pixel type");
}

// Every compression OpenEXR writes, both line orders: the rows per chunk
// the check assumes are OpenEXR's.
TEST_F(ExrReader, ReadsEveryCompressionAndLineOrder) {
    for (int c = 0; c < Imf::NUM_COMPRESSION_METHODS; ++c)
        for (const Imf::LineOrder order : {Imf::INCREASING_Y, Imf::DECREASING_Y}) {
            SCOPED_TRACE(std::to_string(c) + (order == Imf::INCREASING_Y ? " increasing" : " decreasing"));
            const int height = 600;  // more than 2 DWAB chunks of 256 rows
            std::vector<float> values(static_cast<std::size_t>(kWidth) * height);
            for (std::size_t k = 0; k < values.size(); ++k) values[k] = static_cast<float>(k % 256);
            Imf::Header header(kWidth, height);
            header.compression() = static_cast<Imf::Compression>(c);
            header.lineOrder() = order;
            header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
            Imf::FrameBuffer frame;
            frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float),
                                         sizeof(float) * kWidth));
            const fs::path file = folder_ / "c.exr";
            {
                Imf::OutputFile out(file.c_str(), header);
                out.setFrameBuffer(frame);
                out.writePixels(height);
            }
            const ExrChannels exr = read_exr_channels(file);
            ASSERT_EQ(exr.height, height);
            if (c <= Imf::PIZ_COMPRESSION) {  // the lossless ones
                EXPECT_EQ(exr.values[0], values);
            }
        }
}

// Tiled files, every level mode: the first level, as written (the check walks
// every level's tiles, so a level numbered unlike OpenEXR would be refused).
TEST_F(ExrReader, ReadsTiledFilesAsTheirFirstLevel) {
    const fs::path file = folder_ / "tiled.exr";
    for (const Imf::LevelMode mode : {Imf::ONE_LEVEL, Imf::MIPMAP_LEVELS, Imf::RIPMAP_LEVELS})
        for (const Imf::LevelRoundingMode rounding : {Imf::ROUND_DOWN, Imf::ROUND_UP}) {
            SCOPED_TRACE(std::to_string(mode) + " " + std::to_string(rounding));
            test::write_tiled_exr(file, kWidth, kHeight, rgb_, Imf::TileDescription(16, 9, mode, rounding),
                                  Imf::ZIP_COMPRESSION);
            const ExrChannels exr = read_exr_channels(file, {"R", "B"});
            ASSERT_EQ(exr.width, kWidth);
            ASSERT_EQ(exr.height, kHeight);
            ASSERT_EQ(exr.names, (std::vector<std::string>{"B", "R"}));
            for (std::size_t k = 0; k < rgb_.size() / 3; ++k) {
                ASSERT_EQ(exr.values[1][k], rgb_[3 * k]) << k;
                ASSERT_EQ(exr.values[0][k], rgb_[3 * k + 2]) << k;
            }
        }
}

TEST_F(ExrReader, RefusesTilesThatAreNotWhatTheTableSays) {
    // 71 × 49 pixels in 8 × 7 = 56 tiles of 9 × 7, 12 bytes a pixel, uncompressed.
    test::write_tiled_exr(folder_ / "tiled.exr", kWidth, kHeight, rgb_, Imf::TileDescription(9, 7),
                          Imf::NO_COMPRESSION);
    const Bytes tiled = test::read_bytes(folder_ / "tiled.exr");
    const std::size_t table = test::exr_header_end(tiled);
    const auto tile = [&](int k) { return get_le(tiled, table + 8 * static_cast<std::size_t>(k), 8); };
    Bytes bytes = tiled;
    put_le(bytes, table + 8, 8, tile(0));  // tile (0, 0) twice
    expect_refused(bytes, "pixel chunk 1 is tile (0, 0) of level (0, 0), not tile (1, 0) of level (0, 0)");
    bytes = tiled;
    put_le(bytes, tile(0) + 16, 4, 0x7fffffffu);
    expect_refused(bytes, "pixel chunk 0 claims 2147483647 bytes, more than the " +
                              std::to_string(tiled.size() - tile(0) - 20) + " left in the file");
    bytes = tiled;
    bytes.resize(bytes.size() + 4096, 0);
    put_le(bytes, tile(7) + 16, 4, 1000);  // the last tile of the first row is 8 pixels wide
    expect_refused(bytes, "pixel chunk 7 claims 1000 bytes, more than its 8×7 pixels hold uncompressed (672)");
    expect_refused(Bytes(tiled.begin(), tiled.begin() + static_cast<std::ptrdiff_t>(table + 100)),
                   "its line-offset table of 56 entries is cut short");
    const std::size_t description = static_cast<std::size_t>(
        std::search(tiled.begin(), tiled.end(), std::begin("tiledesc"), std::end("tiledesc")) - tiled.begin() + 13);
    bytes = tiled;
    put_le(bytes, description, 4, 1u << 30);  // tiles 2^30 pixels wide
    expect_refused(bytes, "EXR tiles of 1073741824×7 pixels of 12 bytes across 71 pixels are past the reader's limit");
    bytes = tiled;
    bytes[description + 8] = 3;
    expect_refused(bytes, "an EXR file of unknown tile levels 3");
}

// The reproducers fuzz_shard found (fuzz/regressions/shard/): each is read
// or refused with an Error, nothing else.
TEST_F(ExrReader, FuzzReproducersAreRefusedCleanly) {
    const fs::path folder = fs::path(SOMBRA_SOURCE_DIR) / "fuzz" / "regressions" / "shard";
    int count = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
        SCOPED_TRACE(entry.path().string());
        try {
            read_exr_channels(entry.path());
        } catch (const Error&) {
        }
        ++count;
    }
    EXPECT_GE(count, 1);
}

}  // namespace
}  // namespace sombra
