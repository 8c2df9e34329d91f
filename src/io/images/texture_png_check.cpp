// Guards in front of stb_image's PNG decoder. stb grows its buffer for the
// image data to what each IDAT chunk's length claims before reading it, up
// to 2 GiB for a few bytes of file (found by fuzz_gltf): a chunk claiming
// more than the file holds is refused first. And Debian's stb (2022-09) copies
// an IDAT chunk's bytes into its growing buffer with memcpy; for a zero-length
// IDAT before any data that buffer is still null, and memcpy(null, p, 0) is
// undefined behaviour (found by fuzz_texture under UBSan). Empty IDAT chunks
// are legal and carry nothing, so they are dropped from a copy of the file
// handed to stb; files without one before the data (all real ones) are not copied.
#include <cstdint>
#include <string>
#include <string_view>

#include "io/images/stb_guards.h"

namespace sombra {

namespace {

constexpr std::size_t kSignatureSize = 8;
constexpr std::size_t kChunkOverhead = 12;  // length, type, CRC

std::uint32_t big_endian32(const unsigned char* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

// A chunk's length and type at `at`, or false when its header runs past the end.
bool chunk_at(std::span<const unsigned char> bytes, std::size_t at, std::uint32_t& length, std::string_view& type) {
    if (bytes.size() - at < 8) return false;
    length = big_endian32(bytes.data() + at);
    type = std::string_view(reinterpret_cast<const char*>(bytes.data() + at + 4), 4);
    return true;
}

// Where the chunks before the first IDAT with data end, and whether an empty
// IDAT is among them. The walk stops at a malformed chunk: stb judges those.
std::size_t leading_chunks_end(std::span<const unsigned char> bytes, bool& has_empty_idat) {
    has_empty_idat = false;
    std::size_t at = kSignatureSize;
    std::uint32_t length = 0;
    std::string_view type;
    while (at < bytes.size() && chunk_at(bytes, at, length, type)) {
        if (type == "IEND" || (type == "IDAT" && length > 0)) break;
        if (type == "IDAT") has_empty_idat = true;
        if (bytes.size() - at < kChunkOverhead + std::size_t{length}) break;
        at += kChunkOverhead + length;
    }
    return std::min(at, bytes.size());
}

}  // namespace

std::string png_chunk_problem(std::span<const unsigned char> bytes) {
    std::uint32_t length = 0;
    std::string_view type;
    for (std::size_t at = kSignatureSize; at < bytes.size() && chunk_at(bytes, at, length, type);
         at += kChunkOverhead + length) {
        const std::size_t left = bytes.size() - at - 8;  // after the length and type
        if (type == "IDAT" && length > left)
            return "PNG file is truncated: an IDAT chunk claims " + std::to_string(length) + " bytes, " +
                   std::to_string(left) + " are left";
        if (type == "IEND" || left < std::size_t{length} + 4) break;
    }
    return {};
}

std::optional<std::vector<unsigned char>> png_without_leading_empty_idat(std::span<const unsigned char> bytes) {
    if (bytes.size() < kSignatureSize) return std::nullopt;
    bool has_empty_idat = false;
    const std::size_t end = leading_chunks_end(bytes, has_empty_idat);
    if (!has_empty_idat) return std::nullopt;
    std::vector<unsigned char> copy(bytes.begin(), bytes.begin() + kSignatureSize);
    copy.reserve(bytes.size());
    std::uint32_t length = 0;
    std::string_view type;
    for (std::size_t at = kSignatureSize; at < end; at += kChunkOverhead + length) {
        chunk_at(bytes, at, length, type);
        if (type != "IDAT") copy.insert(copy.end(), bytes.begin() + at, bytes.begin() + at + kChunkOverhead + length);
    }
    copy.insert(copy.end(), bytes.begin() + end, bytes.end());
    return copy;
}

}  // namespace sombra
