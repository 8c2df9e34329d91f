// Test helper: the bytes of an EXR file the writer made, to patch its
// line-offset table and pixel chunks (exr_reader_test, shard_merge_test).
#pragma once

#include <cstddef>
#include <cstdint>

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

}  // namespace sombra::test
