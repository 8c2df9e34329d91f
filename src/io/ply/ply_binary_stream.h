// The cursor for a binary PLY body (either byte order), private to
// src/io/ply: it reads the file in slices of kPlyStreamSlice bytes as the
// element readers move on, instead of holding the whole file in memory
// beside the mesh made from it (2 GB for a 100 M-triangle file). Every read
// is checked against the end of the file, and every count the header claims
// against the bytes left on disk, before anything is reserved for it. Errors
// say "file.ply" and the byte offset. It offers the members of
// PlyAsciiCursor (ply_format.h), so the element readers are templates.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "io/ply/ply_format.h"

namespace sombra {

// Bytes read from the file at a time: large enough that reading costs one
// system call per slice, small beside any mesh worth streaming.
inline constexpr std::size_t kPlyStreamSlice = std::size_t{1} << 20;

class PlyBinaryStream {
public:
    // The body starts at byte `body_offset` of `file`, whose size on disk is
    // `file_size`; `already_read` holds the bytes from `body_offset` on that
    // were read with the header. `file` stays the caller's, positioned just
    // after them. `where` (the file's path) must outlive the stream.
    PlyBinaryStream(std::FILE* file, std::string_view already_read, std::uint64_t body_offset, std::uint64_t file_size,
                    bool swap_bytes, const std::string* where);

    // Bytes of the file after the current position, by its size on disk.
    std::size_t remaining() const {
        const std::uint64_t position = offset();
        return file_size_ > position ? static_cast<std::size_t>(file_size_ - position) : 0;
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw Error(*where_, what + " (byte offset " + std::to_string(offset()) + ")");
    }

    // Throws unless `count` records of at least `min_bytes` each fit in the rest of the file.
    void check_count(const PlyElement& element, std::size_t min_bytes) const {
        if (min_bytes > 0 && element.count > remaining() / min_bytes) {
            fail("element '" + element.name + "' claims " + std::to_string(element.count) + " entries of at least " +
                 std::to_string(min_bytes) + " bytes, but only " + std::to_string(remaining()) + " bytes are left");
        }
    }
    static std::size_t min_bytes(const PlyProperty& p) { return ply_type_size(p.is_list ? p.count_type : p.type); }

    double number(PlyType type);

    // A count or an index: must be a whole number (it may be stored as a float).
    std::int64_t integer(PlyType type, const char* what);

    void skip_value(PlyType type) { skip(ply_type_size(type)); }

    // Skips `count` list items, checked against the file's end before moving.
    void skip_items(std::int64_t count, PlyType type) {
        const std::size_t size = ply_type_size(type);
        if (static_cast<std::uint64_t>(count) > remaining() / size)
            fail("list of " + std::to_string(count) + " items runs past the end of the file");
        skip(static_cast<std::size_t>(count) * size);
    }
    // Can `count` list items of `type` still follow?
    bool items_fit(std::int64_t count, PlyType type) const {
        return static_cast<std::uint64_t>(count) <= remaining() / ply_type_size(type);
    }

private:
    std::uint64_t offset() const { return buffer_offset_ + at_; }
    // Makes at least `bytes` (≤ 8) bytes available at at_, reading the next
    // slice; false when the file ends first.
    bool have(std::size_t bytes) { return end_ - at_ >= bytes || refill(bytes); }
    bool refill(std::size_t bytes);
    void skip(std::size_t bytes);

    template <class T>
    T load() {
        if (!have(sizeof(T))) fail("unexpected end of file");
        T value;
        std::memcpy(&value, buffer_.data() + at_, sizeof value);
        at_ += sizeof value;
        if constexpr (sizeof(T) == 2) {
            if (swap_bytes_) value = static_cast<T>(__builtin_bswap16(static_cast<std::uint16_t>(value)));
        } else if constexpr (sizeof(T) == 4) {
            if (swap_bytes_) value = static_cast<T>(__builtin_bswap32(static_cast<std::uint32_t>(value)));
        } else if constexpr (sizeof(T) == 8) {
            if (swap_bytes_) value = static_cast<T>(__builtin_bswap64(static_cast<std::uint64_t>(value)));
        }
        return value;
    }

    std::FILE* file_;
    std::vector<unsigned char> buffer_;  // file bytes [buffer_offset_, buffer_offset_ + end_)
    std::size_t at_ = 0, end_ = 0;
    std::uint64_t buffer_offset_;
    std::uint64_t file_size_;
    bool swap_bytes_;
    const std::string* where_;
};

}  // namespace sombra
