#include "image/tev_packets.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sombra {

namespace {

constexpr std::string_view kChannels[3] = {"R", "G", "B"};

// Appends values in little-endian byte order (tev's wire order, whatever the host's).
struct PacketWriter {
    std::vector<std::uint8_t> bytes;

    // The length's four bytes, filled in by finish(), then the type. (Reserved
    // first: GCC 12 warns, wrongly, of an overflow when a vector that grew by
    // resize() is pushed to.)
    explicit PacketWriter(std::uint8_t type) {
        bytes.reserve(256);
        bytes.insert(bytes.end(), {0, 0, 0, 0, type});
    }
    template <typename T>
    void integer(T value) {
        auto u = static_cast<std::make_unsigned_t<T>>(value);
        for (std::size_t i = 0; i < sizeof(T); ++i) {
            bytes.push_back(static_cast<std::uint8_t>(u & 0xffu));
            u = static_cast<std::make_unsigned_t<T>>(u >> 8);
        }
    }
    void string(std::string_view s) {
        bytes.insert(bytes.end(), s.begin(), s.end());
        bytes.push_back(0);
    }
    void real(float value) {
        std::uint32_t u = 0;
        std::memcpy(&u, &value, sizeof u);
        integer(u);
    }
    std::vector<std::uint8_t> finish() {
        const auto length = static_cast<std::uint32_t>(bytes.size());
        for (std::size_t i = 0; i < 4; ++i) bytes[i] = static_cast<std::uint8_t>(length >> (8 * i));
        return std::move(bytes);
    }
};

}  // namespace

std::vector<std::uint8_t> tev_create_image_packet(std::string_view name, int width, int height) {
    PacketWriter w(kTevCreateImage);
    w.integer<std::uint8_t>(1);  // grab focus: show the render as it starts
    w.string(name);
    w.integer<std::int32_t>(width);
    w.integer<std::int32_t>(height);
    w.integer<std::int32_t>(3);
    for (std::string_view c : kChannels) w.string(c);
    return w.finish();
}

std::vector<std::vector<std::uint8_t>> tev_update_image_packets(std::string_view name, ImageView image) {
    std::vector<std::vector<std::uint8_t>> packets;
    const int rows_per_band = std::max(1, kTevMaxRegionPixels / std::max(1, image.width));
    for (int y0 = 0; y0 < image.height; y0 += rows_per_band) {
        const int rows = std::min(rows_per_band, image.height - y0);
        PacketWriter w(kTevUpdateImageV3);
        w.integer<std::uint8_t>(0);  // grab focus only when created
        w.string(name);
        w.integer<std::int32_t>(3);
        for (std::string_view c : kChannels) w.string(c);
        w.integer<std::int32_t>(0);
        w.integer<std::int32_t>(y0);
        w.integer<std::int32_t>(image.width);
        w.integer<std::int32_t>(rows);
        for (std::int64_t offset = 0; offset < 3; ++offset) w.integer<std::int64_t>(offset);  // interleaved RGB …
        for (int c = 0; c < 3; ++c) w.integer<std::int64_t>(3);                               // … 3 floats a pixel
        const std::size_t first = static_cast<std::size_t>(y0) * static_cast<std::size_t>(image.width) * 3;
        const std::size_t count = static_cast<std::size_t>(rows) * static_cast<std::size_t>(image.width) * 3;
        w.bytes.reserve(w.bytes.size() + 4 * count);
        for (std::size_t i = first; i < first + count; i += 3) {
            const float* p = image.rgb + i;
            const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
            for (int c = 0; c < 3; ++c) w.real(finite ? p[c] : 0.0f);
        }
        packets.push_back(w.finish());
    }
    return packets;
}

}  // namespace sombra
