// Test helper: the bytes of an EXR file the writer made, to patch its
// line-offset table and pixel chunks (exr_reader_test, shard_merge_test), and
// tiled files, which sombra's writer never makes (exr_reader_test, hdr_image_test).
#pragma once

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfTiledOutputFile.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace sombra::test {

// Little-endian integers of `count` bytes; Bytes is any container of chars or bytes.
template <class Bytes>
std::uint64_t get_le(const Bytes& bytes, std::size_t at, int count) {
    std::uint64_t v = 0;
    for (int k = count - 1; k >= 0; --k)
        v = v << 8 | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(k)]);
    return v;
}
template <class Bytes>
void put_le(Bytes& bytes, std::size_t at, int count, std::uint64_t v) {
    for (int k = 0; k < count; ++k, v >>= 8)
        bytes[at + static_cast<std::size_t>(k)] = static_cast<typename Bytes::value_type>(v & 0xffu);
}

// Where the header of a well-formed single-part file ends: its line-offset table.
template <class Bytes>
std::size_t exr_header_end(const Bytes& bytes) {
    std::size_t at = 8;
    const auto skip_string = [&] {  // false for the empty name that ends the header
        const std::size_t start = at;
        while (bytes[at] != 0) ++at;
        return ++at - start > 1;
    };
    while (skip_string()) {
        skip_string();
        at += 4 + get_le(bytes, at, 4);
    }
    return at;
}

// Where pixel chunk `k` starts (its row, then its size, then its data).
template <class Bytes>
std::size_t exr_chunk(const Bytes& bytes, int k) {
    return get_le(bytes, exr_header_end(bytes) + 8 * static_cast<std::size_t>(k), 8);
}

// Writes `rgb` (width × height, 3 floats per pixel) as the first level of a
// tiled float R, G, B file whose data window starts at (3, -2); each smaller
// level `tiles` asks for holds lx + 10 ly in every value.
inline void write_tiled_exr(const std::filesystem::path& file, int width, int height, const std::vector<float>& rgb,
                            const Imf::TileDescription& tiles, Imf::Compression compression) {
    const Imath::V2i origin(3, -2);
    const Imath::Box2i window(origin, origin + Imath::V2i(width - 1, height - 1));
    Imf::Header header(window, window);
    header.setTileDescription(tiles);
    header.compression() = compression;
    const char* names[3] = {"R", "G", "B"};
    for (const char* name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    Imf::TiledOutputFile out(file.c_str(), header);
    for (int ly = 0; ly < out.numYLevels(); ++ly)
        for (int lx = 0; lx < out.numXLevels(); ++lx) {
            if (!out.isValidLevel(lx, ly)) continue;
            const Imath::Box2i level = out.dataWindowForLevel(lx, ly);
            const int w = level.max.x - level.min.x + 1, h = level.max.y - level.min.y + 1;
            std::vector<float> values =
                lx == 0 && ly == 0 ? rgb : std::vector<float>(static_cast<std::size_t>(w) * h * 3, float(lx + 10 * ly));
            Imf::FrameBuffer frame;
            for (std::size_t c = 0; c < 3; ++c)
                frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, values.data() + c, level, 12,
                                                        12 * static_cast<std::size_t>(w)));
            out.setFrameBuffer(frame);
            out.writeTiles(0, out.numXTiles(lx) - 1, 0, out.numYTiles(ly) - 1, lx, ly);
        }
}

}  // namespace sombra::test
