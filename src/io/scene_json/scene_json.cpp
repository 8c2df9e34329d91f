// JSON text → nlohmann::json with positioned syntax errors, and typed readers
// that name the JSON pointer of whatever is wrong.
#include "io/scene_json/scene_json.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace sombra {
namespace {

// Deeper than any scene needs; stops pathological files early.
constexpr std::size_t kMaxNesting = 64;
// Longest parser message kept: the parser quotes the token it read, which can
// be a whole unterminated string.
constexpr std::size_t kMaxMessage = 160;
// Longest WHERE or message built from the file's own keys and strings.
constexpr std::size_t kMaxEcho = 400;

// Messages echo keys, names and tokens from the file: keep them on one line
// and of bounded length, whatever the file holds.
std::string one_line(std::string text, std::size_t max_size, bool ascii_only) {
    for (char& c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f || (ascii_only && byte >= 0x80)) c = '?';
    }
    if (text.size() > max_size) {
        while (max_size > 0 && (static_cast<unsigned char>(text[max_size]) & 0xc0) == 0x80)
            --max_size;  // whole UTF-8 characters
        text = text.substr(0, max_size) + "...";
    }
    return text;
}

// "[json.exception.parse_error.101] parse error at line 1, column 6: syntax
// error ..." → "syntax error ...". The parser quotes raw bytes it could not
// read, possibly broken UTF-8: those become '?'.
std::string short_parser_message(const std::string& full) {
    std::string msg = full;
    if (const auto close = msg.find("] "); msg.rfind("[json.exception.", 0) == 0 && close != std::string::npos)
        msg.erase(0, close + 2);
    if (msg.rfind("parse error", 0) == 0)
        if (const auto colon = msg.find(": "); colon != std::string::npos) msg.erase(0, colon + 2);
    return one_line(std::move(msg), kMaxMessage, true);
}

// 1-based line and byte column of the byte at `index` (clamped to the text's end).
std::string line_col(const std::string& text, std::size_t index) {
    index = std::min(index, text.size());
    const auto begin = text.begin();
    const auto line = 1 + std::count(begin, begin + static_cast<std::ptrdiff_t>(index), '\n');
    const auto last_newline = text.rfind('\n', index == 0 ? std::string::npos : index - 1);
    const std::size_t line_start = (index == 0 || last_newline == std::string::npos) ? 0 : last_newline + 1;
    return std::to_string(line) + ":" + std::to_string(index - line_start + 1);
}

// A validating pass over the text: nlohmann keeps the last of duplicate keys
// silently, and reports number overflow without a position unless asked
// through SAX. Tracks the JSON pointer of the value being read.
class SceneSyntaxCheck final : public nlohmann::json_sax<Json> {
public:
    // Set when the pass stopped.
    bool failed = false;
    bool syntax = false;         // syntax error at `byte_index`
    std::size_t byte_index = 0;  // 0-based
    std::string pointer;         // for non-syntax failures
    std::string message;

    bool null() override { return element(); }
    bool boolean(bool) override { return element(); }
    bool number_integer(number_integer_t) override { return element(); }
    bool number_unsigned(number_unsigned_t) override { return element(); }
    bool number_float(number_float_t, const string_t&) override { return element(); }
    bool string(string_t&) override { return element(); }
    bool binary(binary_t&) override { return element(); }
    bool start_object(std::size_t) override { return element() && open(true); }
    bool start_array(std::size_t) override { return element() && open(false); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }

    bool key(string_t& k) override {
        Frame& f = stack_.back();
        if (!f.keys.insert(k).second) {
            pointer = json_child(current_pointer(stack_.size() - 1), k);
            return fail("duplicate key '" + k + "'");
        }
        f.last_key = k;
        return true;
    }

    bool parse_error(std::size_t position, const std::string& last_token,
                     const nlohmann::json::exception& ex) override {
        failed = true;
        syntax = true;
        // position counts bytes read, 1-based. Number overflow (406) is reported
        // after its token: point at the token's start instead.
        if (ex.id == 406 && last_token.size() <= position)
            byte_index = position - last_token.size();
        else
            byte_index = position == 0 ? 0 : position - 1;
        message = short_parser_message(ex.what());
        return false;
    }

private:
    struct Frame {
        bool is_object;
        std::set<std::string> keys;
        std::string last_key;
        std::size_t elements = 0;  // arrays: elements seen so far
    };
    std::vector<Frame> stack_;

    bool element() {
        if (!stack_.empty() && !stack_.back().is_object) ++stack_.back().elements;
        return true;
    }
    bool open(bool is_object) {
        if (stack_.size() >= kMaxNesting) {
            pointer = current_pointer(stack_.size());
            return fail("nested deeper than " + std::to_string(kMaxNesting) + " levels");
        }
        stack_.push_back(Frame{is_object, {}, {}, 0});
        return true;
    }
    bool close() {
        stack_.pop_back();
        return true;
    }
    bool fail(std::string what) {
        failed = true;
        message = std::move(what);
        return false;
    }
    // Pointer of the value currently being read inside the first `depth` frames.
    std::string current_pointer(std::size_t depth) const {
        std::string p;
        for (std::size_t i = 0; i < depth; ++i) {
            const Frame& f = stack_[i];
            p = f.is_object ? json_child(p, f.last_key) : json_child(p, f.elements - 1);
        }
        return p;
    }
};

}  // namespace

Json parse_scene_json(const std::string& text, const std::string& name) {
    SceneSyntaxCheck check;
    Json::sax_parse(text, &check);
    if (check.failed) {
        if (check.syntax) throw Error(name + ":" + line_col(text, check.byte_index), check.message);
        const std::string where = check.pointer.empty() ? name : name + ": " + one_line(check.pointer, kMaxEcho, false);
        throw Error(where, one_line(check.message, kMaxEcho, false));
    }
    try {
        return Json::parse(text);
    } catch (const nlohmann::json::exception& ex) {  // not expected after the check above
        throw Error(name, short_parser_message(ex.what()));
    }
}

std::string json_where(const SceneJson& s, std::string_view pointer) {
    if (pointer.empty()) return s.name;
    return s.name + ": " + std::string(pointer);
}

void json_fail(const SceneJson& s, std::string_view pointer, const std::string& what) {
    throw Error(json_where(s, one_line(std::string(pointer), kMaxEcho, false)), one_line(what, kMaxEcho, false));
}

void json_warn(const SceneJson& s, std::string_view pointer, const std::string& what) {
    s.diag.warn(json_where(s, one_line(std::string(pointer), kMaxEcho, false)), one_line(what, kMaxEcho, false));
}

std::string looked_for(const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    return "(looked for " + (ec ? path : absolute.lexically_normal()).string() + ", relative to the scene's folder)";
}

std::string json_child(std::string_view pointer, std::string_view key) {
    std::string p(pointer);
    p += '/';
    for (char c : key) {
        if (c == '~')
            p += "~0";
        else if (c == '/')
            p += "~1";
        else
            p += c;
    }
    return p;
}

std::string json_child(std::string_view pointer, std::size_t index) {
    return std::string(pointer) + "/" + std::to_string(index);
}

void expect_object(const SceneJson& s, const Json& v, std::string_view pointer) {
    if (!v.is_object()) json_fail(s, pointer, "expected an object");
}

void expect_array(const SceneJson& s, const Json& v, std::string_view pointer) {
    if (!v.is_array()) json_fail(s, pointer, "expected an array");
}

void expect_keys(const SceneJson& s, const Json& object, std::string_view pointer,
                 std::initializer_list<std::string_view> allowed) {
    expect_object(s, object, pointer);
    for (const auto& [key, value] : object.items()) {
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
            json_fail(s, json_child(pointer, key), "unknown key '" + key + "'");
    }
}

const Json* find_member(const Json& object, std::string_view key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

const Json& require_member(const SceneJson& s, const Json& object, std::string_view pointer, std::string_view key) {
    const Json* v = find_member(object, key);
    if (!v) json_fail(s, json_child(pointer, key), "missing required key '" + std::string(key) + "'");
    return *v;
}

float read_float(const SceneJson& s, const Json& v, std::string_view pointer) {
    if (!v.is_number()) json_fail(s, pointer, "expected a number");
    const double d = v.get<double>();
    const float f = static_cast<float>(d);
    if (!std::isfinite(d) || !std::isfinite(f)) json_fail(s, pointer, "number out of range");
    return f;
}

std::int64_t read_integer(const SceneJson& s, const Json& v, std::string_view pointer, std::int64_t lo,
                          std::int64_t hi) {
    if (!v.is_number_integer()) json_fail(s, pointer, "expected an integer");
    const bool too_big = v.is_number_unsigned() &&
                         v.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    const std::int64_t i = too_big ? std::numeric_limits<std::int64_t>::max() : v.get<std::int64_t>();
    if (i < lo || i > hi) json_fail(s, pointer, "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return i;
}

std::uint64_t read_unsigned(const SceneJson& s, const Json& v, std::string_view pointer) {
    if (!v.is_number_integer()) json_fail(s, pointer, "expected an integer");
    if (!v.is_number_unsigned()) json_fail(s, pointer, "must be non-negative");
    return v.get<std::uint64_t>();
}

Vec3 read_vec3(const SceneJson& s, const Json& v, std::string_view pointer) {
    if (!v.is_array() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](const Json& e) { return e.is_number(); }))
        json_fail(s, pointer, "expected an array of 3 numbers");
    return {read_float(s, v[0], json_child(pointer, 0)), read_float(s, v[1], json_child(pointer, 1)),
            read_float(s, v[2], json_child(pointer, 2))};
}

Vec3 read_rgb(const SceneJson& s, const Json& v, std::string_view pointer) {
    const Vec3 c = read_vec3(s, v, pointer);
    if (min_component(c) < 0) json_fail(s, pointer, "colour components must be non-negative");
    return c;
}

const std::string& read_string(const SceneJson& s, const Json& v, std::string_view pointer) {
    if (!v.is_string()) json_fail(s, pointer, "expected a string");
    return v.get_ref<const std::string&>();
}

}  // namespace sombra
