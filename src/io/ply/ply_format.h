// The PLY format for the loader (spec §9), private to src/io/ply: the header
// (format, elements and their properties in file order), and the cursor
// that reads values from an ascii body, with every read checked against the
// end of the file and errors that say where: "file.ply:LINE". Binary bodies
// (either byte order) are read by PlyBinaryStream (ply_binary_stream.h),
// which offers the same members, so the element readers are templates.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
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
