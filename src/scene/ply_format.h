// The PLY format for the loader (spec §9), private to src/scene: the header
// (format, elements and their properties in file order), and cursors that
// read values from the body, binary (either byte order) or ascii, with every
// read checked against the end of the file and errors that say where:
// "file.ply" and the byte offset for binary, "file.ply:LINE" for ascii. Both
// cursors offer the same members, so the element readers are templates.
#pragma once

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace sombra {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

// Bytes of one value of `type` in a binary body.
std::size_t ply_type_size(PlyType type);

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;  // the value type; for a list, the type of its items
    bool is_list = false;
    PlyType count_type = PlyType::UInt8;  // lists only: the type of the leading item count
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;  // as claimed by the header: not yet checked against the body
    std::vector<PlyProperty> properties;
    int line = 0;  // header line declaring it

    // Index into properties of the property named `name`, or -1.
    int find(std::string_view property_name) const;
};

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    std::size_t body_offset = 0;  // byte offset of the body: just after the end_header line
    int body_line = 0;            // line number of the body's first line
};

// Parses the header at the start of `text`. Throws Error("WHERE:LINE", ...)
// for anything that is not a PLY 1.0 header, with `where` the file's path.
PlyHeader parse_ply_header(std::string_view text, const std::string& where);

struct PlyBinaryCursor {
    const unsigned char* file_begin;  // for byte offsets in messages
    const unsigned char* at;
    const unsigned char* end;
    bool swap_bytes;  // the file's byte order is not the machine's
    const std::string* where;

    std::size_t remaining() const { return static_cast<std::size_t>(end - at); }

    [[noreturn]] void fail(const std::string& what) const {
        throw Error(*where, what + " (byte offset " + std::to_string(at - file_begin) + ")");
    }

    // Throws unless `count` records of at least `min_bytes` each fit in the rest of the file.
    void check_count(const PlyElement& element, std::size_t min_bytes) const {
        if (min_bytes > 0 && element.count > remaining() / min_bytes) {
            fail("element '" + element.name + "' claims " + std::to_string(element.count) + " entries of at least " +
                 std::to_string(min_bytes) + " bytes, but only " + std::to_string(remaining()) + " bytes are left");
        }
    }
    static std::size_t min_bytes(const PlyProperty& p) { return ply_type_size(p.is_list ? p.count_type : p.type); }

    double number(PlyType type) {
        switch (type) {
            case PlyType::Int8: return load<std::int8_t>();
            case PlyType::UInt8: return load<std::uint8_t>();
            case PlyType::Int16: return load<std::int16_t>();
            case PlyType::UInt16: return load<std::uint16_t>();
            case PlyType::Int32: return load<std::int32_t>();
            case PlyType::UInt32: return load<std::uint32_t>();
            case PlyType::Float32: return std::bit_cast<float>(load<std::uint32_t>());
            case PlyType::Float64: return std::bit_cast<double>(load<std::uint64_t>());
        }
        return 0;
    }

    // A count or an index: must be a whole number (it may be stored as a float).
    std::int64_t integer(PlyType type, const char* what) {
        const double value = number(type);
        if (!(std::fabs(value) < 9e15) || value != std::floor(value)) {
            at -= ply_type_size(type);
            fail(std::string(what) + " is not an integer");
        }
        return static_cast<std::int64_t>(value);
    }

    void skip_value(PlyType type) { skip(ply_type_size(type)); }

    // Skips `count` list items, checked against the file's end before moving.
    void skip_items(std::int64_t count, PlyType type) {
        const std::size_t size = ply_type_size(type);
        if (static_cast<std::uint64_t>(count) > remaining() / size)
            fail("list of " + std::to_string(count) + " items runs past the end of the file");
        at += static_cast<std::size_t>(count) * size;
    }
    // Can `count` list items of `type` still follow?
    bool items_fit(std::int64_t count, PlyType type) const {
        return static_cast<std::uint64_t>(count) <= remaining() / ply_type_size(type);
    }

private:
    void skip(std::size_t bytes) {
        if (bytes > remaining()) fail("unexpected end of file");
        at += bytes;
    }
    template <class T>
    T load() {
        if (sizeof(T) > remaining()) fail("unexpected end of file");
        T value;
        std::memcpy(&value, at, sizeof value);
        at += sizeof value;
        if constexpr (sizeof(T) == 2) {
            if (swap_bytes) value = static_cast<T>(__builtin_bswap16(static_cast<std::uint16_t>(value)));
        } else if constexpr (sizeof(T) == 4) {
            if (swap_bytes) value = static_cast<T>(__builtin_bswap32(static_cast<std::uint32_t>(value)));
        } else if constexpr (sizeof(T) == 8) {
            if (swap_bytes) value = static_cast<T>(__builtin_bswap64(static_cast<std::uint64_t>(value)));
        }
        return value;
    }
};

struct PlyAsciiCursor {
    const char* at;
    const char* end;
    int line;  // of the current position
    const std::string* where;

    std::size_t remaining() const { return static_cast<std::size_t>(end - at); }

    [[noreturn]] void fail(const std::string& what) const { throw Error(*where + ":" + std::to_string(line), what); }

    // Every value takes at least one character and one separator.
    void check_count(const PlyElement& element, std::size_t min_tokens) const {
        if (min_tokens > 0 && element.count > (remaining() + 1) / (2 * min_tokens)) {
            fail("element '" + element.name + "' claims " + std::to_string(element.count) + " entries, but only " +
                 std::to_string(remaining()) + " bytes are left");
        }
    }
    static std::size_t min_bytes(const PlyProperty&) { return 1; }  // one token each

    std::string_view token() {
        while (at < end && is_space(*at)) line += *at++ == '\n';
        if (at == end) fail("unexpected end of file");
        const char* begin = at;
        while (at < end && !is_space(*at)) ++at;
        return {begin, static_cast<std::size_t>(at - begin)};
    }

    double number(PlyType) {
        const std::string_view text = token();
        std::string_view digits = text;
        if (digits.size() > 1 && digits[0] == '+') digits.remove_prefix(1);  // from_chars takes no '+'
        double value = 0;
        const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec == std::errc::result_out_of_range)
            return std::strtod(std::string(digits).c_str(), nullptr);  // ±inf or ~0
        if (ec != std::errc() || ptr != digits.data() + digits.size())
            fail("expected a number, got '" + std::string(text.substr(0, 32)) + "'");
        return value;
    }

    std::int64_t integer(PlyType type, const char* what) {
        const double value = number(type);
        if (!(std::fabs(value) < 9e15) || value != std::floor(value)) fail(std::string(what) + " is not an integer");
        return static_cast<std::int64_t>(value);
    }

    void skip_value(PlyType) { token(); }

    void skip_items(std::int64_t count, PlyType) {
        for (std::int64_t i = 0; i < count; ++i) token();
    }
    bool items_fit(std::int64_t count, PlyType) const {
        return static_cast<std::uint64_t>(count) <= (remaining() + 1) / 2;
    }

private:
    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }
};

}  // namespace sombra
