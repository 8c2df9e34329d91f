// tev's protocol as sombra writes it, read back by an independent decoder
// (tev_test_decoder.h) that paints the updates as tev would.
#include "image/tev_packets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "image/tev_test_decoder.h"

namespace sombra {
namespace {

std::vector<float> ramp(int width, int height) {
    std::vector<float> rgb(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.001f * static_cast<float>(i) - 1.5f;
    return rgb;
}

void feed(testing::TevDecoder& decoder, const std::vector<std::uint8_t>& packet) {
    decoder.feed(packet.data(), packet.size());
}

TEST(TevPackets, CreateThenUpdateRebuildsTheImage) {
    const int width = 7, height = 5;
    const std::vector<float> rgb = ramp(width, height);
    testing::TevDecoder decoder;
    feed(decoder, tev_create_image_packet("cornell.png", width, height));
    for (const auto& p : tev_update_image_packets("cornell.png", ImageView{width, height, rgb.data()}))
        feed(decoder, p);
    ASSERT_EQ(decoder.images.count("cornell.png"), 1u);
    const testing::TevImage& image = decoder.images["cornell.png"];
    EXPECT_EQ(image.width, width);
    EXPECT_EQ(image.height, height);
    EXPECT_EQ(image.channels, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_EQ(image.values, rgb);
    EXPECT_EQ(image.updates, 1);
    EXPECT_FALSE(decoder.has_partial_packet());
}

TEST(TevPackets, LengthFieldCountsTheWholePacketLittleEndian) {
    const std::vector<std::uint8_t> p = tev_create_image_packet("a", 2, 3);
    // 4 length + 1 type + 1 focus + "a\0" + 3 × int32 + "R\0G\0B\0"
    ASSERT_EQ(p.size(), 4u + 1 + 1 + 2 + 12 + 6);
    EXPECT_EQ(p[0], p.size());
    EXPECT_EQ(p[1], 0);
    EXPECT_EQ(p[4], kTevCreateImage);
    EXPECT_EQ(p[8], 2);  // width's low byte, after "a\0"
}

TEST(TevPackets, LargeImagesGoInBandsOfWholeRows) {
    const int width = 300, height = 500;  // 150,000 pixels: three bands of at most 65,536
    const std::vector<float> rgb = ramp(width, height);
    const auto packets = tev_update_image_packets("big", ImageView{width, height, rgb.data()});
    EXPECT_EQ(packets.size(), 3u);
    testing::TevDecoder decoder;
    feed(decoder, tev_create_image_packet("big", width, height));
    // Delivered a few bytes at a time, as TCP may: the decoder waits for whole packets.
    for (const auto& p : packets)
        for (std::size_t at = 0; at < p.size(); at += 4093)
            decoder.feed(p.data() + at, std::min<std::size_t>(4093, p.size() - at));
    EXPECT_EQ(decoder.images["big"].values, rgb);
    EXPECT_EQ(decoder.images["big"].updates, 3);
}

TEST(TevPackets, NonFinitePixelsAreSentBlack) {
    std::vector<float> rgb = {1,    2,    3,     std::numeric_limits<float>::quiet_NaN(),
                              0.5f, 0.5f, 0.25f, std::numeric_limits<float>::infinity(),
                              0,    4,    5,     6};
    testing::TevDecoder decoder;
    feed(decoder, tev_create_image_packet("x", 2, 2));
    for (const auto& p : tev_update_image_packets("x", ImageView{2, 2, rgb.data()})) feed(decoder, p);
    EXPECT_EQ(decoder.images["x"].values, (std::vector<float>{1, 2, 3, 0, 0, 0, 0, 0, 0, 4, 5, 6}));
}

}  // namespace
}  // namespace sombra
