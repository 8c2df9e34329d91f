// check_exr_file (exr_check.h): sombra's own walk of an OpenEXR file's
// layout (magic, version, header, line-offset table, the first bytes of each
// chunk), so that no size OpenEXR allocates is taken on the file's word.
#include "image/exr_check.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/image_limits.h"

namespace sombra {

namespace {

// The types OpenEXR reads as fixed-size values whatever length the attribute
// claims: another length would have it read the rest of the header
// differently from this walk.
constexpr std::pair<std::string_view, std::uint32_t> kFixedSizes[] = {
    {"box2i", 16},      {"box2f", 16},   {"chromaticities", 32},
    {"compression", 1}, {"double", 8},   {"envmap", 1},
    {"float", 4},       {"int", 4},      {"keycode", 28},
    {"lineOrder", 1},   {"m33f", 36},    {"m33d", 72},
    {"m44f", 64},       {"m44d", 128},   {"rational", 8},
    {"tiledesc", 9},    {"timecode", 8}, {"v2i", 8},
    {"v2f", 8},         {"v2d", 16},     {"v3i", 12},
    {"v3f", 12},        {"v3d", 24},     {"deepImageState", 1}};

// Rows per pixel chunk of each compression OpenEXR 3 knows, by its number
// (NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA, DWAB).
constexpr std::array<std::int64_t, 10> kRowsPerChunk = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};

// OpenEXR allocates a chunk's buffers (about three times its uncompressed
// size) when it opens the file, from the data window's width and the channel
// list alone. sombra's shards (16-row ZIP chunks, at most 14 float channels)
// stay under 30 MiB at the widest image; this allows 128 such channels.
constexpr std::int64_t kMaxChunkBytes = std::int64_t{1} << 28;

// a × b × c ≤ limit, for factors below 2^32 (a tile's sides are 32-bit).
bool product_at_most(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t limit) {
    if (a == 0 || b == 0 || c == 0) return true;
    return a <= limit / b && a * b <= limit / c;
}

// The file's bytes at `at`, read on demand (a shard's pixels can be large).
class FileBytes {
public:
    FileBytes(const std::filesystem::path& path, const std::string& where)
        : in_(path, std::ios::binary), where_(where) {
        if (!in_) throw Error(where, "cannot read it");
        in_.seekg(0, std::ios::end);
        size_ = static_cast<std::uint64_t>(std::max<std::streamoff>(in_.tellg(), 0));
    }
    std::uint64_t size() const { return size_; }
    std::vector<unsigned char> read(std::uint64_t at, std::uint64_t count) {
        std::vector<unsigned char> out(static_cast<std::size_t>(count));
        in_.seekg(static_cast<std::streamoff>(at));
        in_.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(count));
        if (!in_) throw Error(where_, "cannot read it");
        return out;
    }

private:
    std::ifstream in_;
    std::string where_;
    std::uint64_t size_ = 0;
};

std::uint64_t little_endian(const std::vector<unsigned char>& bytes, std::size_t at, int count) {
    std::uint64_t v = 0;
    for (int k = count - 1; k >= 0; --k) v = v << 8 | bytes[at + static_cast<std::size_t>(k)];
    return v;
}
std::uint32_t u32(const std::vector<unsigned char>& bytes, std::size_t at) {
    return static_cast<std::uint32_t>(little_endian(bytes, at, 4));
}
std::int64_t i32(const std::vector<unsigned char>& bytes, std::size_t at) {
    return static_cast<std::int32_t>(u32(bytes, at));
}

// A tiled file's "tiles" attribute: the tile size and its levels.
struct Tiles {
    std::int64_t width = 0, height = 0;  // 0 for a scanline file
    int level_mode = 0;                  // ONE_LEVEL, MIPMAP_LEVELS, RIPMAP_LEVELS
    bool round_up = false;               // how a level's size is rounded (ROUND_UP, else ROUND_DOWN)
};

// What the chunk walk needs from the header.
struct Layout {
    std::uint64_t header_end = 0;  // where the line-offset table starts
    std::int64_t rows_per_chunk = 0, min_y = 0, width = 0, height = 0;
    std::int64_t bytes_per_pixel = 0;  // every channel at full resolution: an upper bound
    Tiles tiles;
};

Layout walk_header(FileBytes& file, const std::string& where) {
    // The header is small (a sombra shard's is under 1 KiB).
    const std::vector<unsigned char> bytes = file.read(0, std::min<std::uint64_t>(file.size(), 1 << 20));
    if (bytes.size() < 8 || u32(bytes, 0) != 20000630u)
        throw Error(where, "cannot read as OpenEXR: it does not start with OpenEXR's magic number");
    const std::uint32_t flags = u32(bytes, 4);
    if ((flags & 0xffu) != 2u || (flags & 0x1800u) != 0u)
        throw Error(where, "not a single-part flat EXR file of version 2");
    const bool tiled = (flags & 0x200u) != 0u;
    std::size_t at = 8;
    const auto c_string = [&](std::size_t end) {
        const std::size_t start = at;
        while (at < end && bytes[at] != '\0') ++at;
        if (at >= end || at - start > 255) throw Error(where, "damaged EXR header");
        return std::string(bytes.begin() + static_cast<std::ptrdiff_t>(start),
                           bytes.begin() + static_cast<std::ptrdiff_t>(at++));
    };
    Layout layout;
    std::int64_t compression = -1;
    bool has_window = false, has_channels = false, has_tiles = false;
    int tile_mode = 0;  // the level mode in the low 4 bits, the rounding mode above
    std::set<std::string> names;
    while (true) {
        const std::string name = c_string(bytes.size());
        if (name.empty()) break;  // the header's end
        const std::string type = c_string(bytes.size());
        if (at + 4 > bytes.size()) throw Error(where, "damaged EXR header");
        const std::uint32_t length = u32(bytes, at);
        at += 4;
        if (length > bytes.size() - at)
            throw Error(where, "damaged EXR header: attribute '" + name + "' claims " + std::to_string(length) +
                                   " bytes past the file");
        // OpenEXR reads a second value into the first (channel lists add up).
        if (!names.insert(name).second) throw Error(where, "damaged EXR header: attribute '" + name + "' given twice");
        const std::size_t end = at + length;
        const auto wrong_length = [&] {
            return Error(where, "damaged EXR header: attribute '" + name + "' of type " + type + " has " +
                                    std::to_string(length) + " bytes");
        };
        for (const auto& [fixed_type, size] : kFixedSizes)
            if (type == fixed_type && length != size) throw wrong_length();
        if (type == "box2i") {
            const auto coordinate = [&](std::size_t k) { return i32(bytes, at + 4 * k); };
            const std::int64_t width = coordinate(2) - coordinate(0) + 1, height = coordinate(3) - coordinate(1) + 1;
            const std::string size = std::to_string(width) + "×" + std::to_string(height);
            if (width <= 0 || height <= 0) throw Error(where, "EXR " + name + " has no pixels (" + size + ")");
            if (width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxPixels)
                throw Error(where, "EXR " + name + " is " + size + " pixels, more than the limit of " +
                                       std::to_string(kMaxImageSide) + " per side and " + std::to_string(kMaxPixels) +
                                       " in all");
            if (name == "dataWindow") {
                layout.min_y = coordinate(1), layout.width = width, layout.height = height;
                has_window = true;
            }
        } else if (type == "compression" && name == "compression") {
            compression = bytes[at];
        } else if (type == "tiledesc" && name == "tiles") {
            layout.tiles = {u32(bytes, at), u32(bytes, at + 4), bytes[at + 8] & 0xf, (bytes[at + 8] >> 4) == 1};
            tile_mode = bytes[at + 8];
            has_tiles = true;
        } else if (type == "chlist") {
            // Names and 16-byte descriptions up to an empty name, which OpenEXR
            // looks for whatever the length: it must be the attribute's last byte.
            std::int64_t bytes_per_pixel = 0;
            for (std::string channel = c_string(end); !channel.empty(); channel = c_string(end)) {
                if (end - at < 16) throw wrong_length();
                const std::uint32_t pixel_type = u32(bytes, at);  // UINT, HALF, FLOAT
                if (pixel_type > 2) throw Error(where, "EXR channel '" + channel + "' has an unknown pixel type");
                bytes_per_pixel += pixel_type == 1 ? 2 : 4;
                at += 16;
            }
            if (at != end) throw wrong_length();
            if (name == "channels") layout.bytes_per_pixel = bytes_per_pixel, has_channels = true;
        } else if (type == "preview") {  // OpenEXR allocates its width × height pixels
            if (length < 8) throw wrong_length();
            const std::uint64_t pixels = std::uint64_t{u32(bytes, at)} * u32(bytes, at + 4);  // < 2^64
            if ((length - 8) % 4 != 0 || pixels != (length - 8) / 4) throw wrong_length();
        } else if (type == "floatvector" && length % 4 != 0) {
            throw wrong_length();
        } else if (type == "idmanifest") {  // its length is read differently across OpenEXR 3 versions
            throw Error(where, "an EXR attribute of type idmanifest ('" + name + "'), which sombra does not read");
        }
        at = end;
    }
    for (const auto& [present, what] : {std::pair{has_channels, "channels"}, std::pair{compression >= 0, "compression"},
                                        std::pair{has_window, "dataWindow"}})
        if (!present) throw Error(where, std::string("damaged EXR header: no '") + what + "' attribute");
    if (compression >= static_cast<std::int64_t>(kRowsPerChunk.size()))
        throw Error(where, "an EXR file of unknown compression " + std::to_string(compression));
    layout.header_end = at;
    layout.rows_per_chunk = kRowsPerChunk[static_cast<std::size_t>(compression)];
    if (!tiled) {
        layout.tiles = {};
        return layout;
    }
    if (!has_tiles) throw Error(where, "damaged EXR header: no 'tiles' attribute in a tiled file");
    if ((tile_mode & 0xf) > 2 || (tile_mode >> 4) > 1)
        throw Error(where, "an EXR file of unknown tile levels " + std::to_string(tile_mode));
    const Tiles& tiles = layout.tiles;
    if (tiles.width < 1 || tiles.height < 1)
        throw Error(where, "damaged EXR header: tiles of " + std::to_string(tiles.width) + "×" +
                               std::to_string(tiles.height) + " pixels");
    // One tile's buffers, and a row of tiles across the image, which OpenEXR
    // keeps to hand out scanlines, within the limit of one chunk.
    if (!product_at_most(static_cast<std::uint64_t>(std::max(tiles.width, layout.width)),
                         static_cast<std::uint64_t>(tiles.height),
                         static_cast<std::uint64_t>(std::max<std::int64_t>(layout.bytes_per_pixel, 1)), kMaxChunkBytes))
        throw Error(where, "EXR tiles of " + std::to_string(tiles.width) + "×" + std::to_string(tiles.height) +
                               " pixels of " + std::to_string(layout.bytes_per_pixel) + " bytes across " +
                               std::to_string(layout.width) + " pixels are past the reader's limit of " +
                               std::to_string(kMaxChunkBytes >> 20) + " MiB");
    layout.rows_per_chunk = tiles.height;
    return layout;
}

// The levels of a tiled file as OpenEXR numbers them (ImfTiledMisc.cpp), in
// the order of its line-offset table; a scanline file's one level.
struct Level {
    std::int64_t x = 0, y = 0;           // the level's number across and down
    std::int64_t width = 0, height = 0;  // its pixels
    std::int64_t columns = 0, rows = 0;  // its chunks across and down
};

// log2(n) rounded down, or up (a level's rounding mode).
std::int64_t round_log2(std::int64_t n, bool up) {
    std::int64_t log = 0;
    bool inexact = false;
    for (; n > 1; n >>= 1, ++log) inexact = inexact || (n & 1) != 0;
    return log + (up && inexact ? 1 : 0);
}

std::vector<Level> levels_of(const Layout& h) {
    const auto chunks = [](std::int64_t pixels, std::int64_t per_chunk) {
        return (pixels + per_chunk - 1) / per_chunk;
    };
    const Tiles& t = h.tiles;
    if (t.width == 0) return {Level{0, 0, h.width, h.height, 1, chunks(h.height, h.rows_per_chunk)}};
    const auto size = [&](std::int64_t pixels, std::int64_t level) {
        std::int64_t n = pixels >> level;
        if (t.round_up && (n << level) < pixels) ++n;
        return std::max<std::int64_t>(n, 1);
    };
    std::int64_t across = 1, down = 1;  // ONE_LEVEL
    if (t.level_mode == 1) across = down = round_log2(std::max(h.width, h.height), t.round_up) + 1;
    if (t.level_mode == 2) across = round_log2(h.width, t.round_up) + 1, down = round_log2(h.height, t.round_up) + 1;
    std::vector<Level> levels;
    for (std::int64_t y = 0; y < down; ++y)
        for (std::int64_t x = 0; x < across; ++x) {
            if (t.level_mode == 1 && x != y) continue;  // mip-map levels shrink both ways at once
            const std::int64_t width = size(h.width, x), height = size(h.height, y);
            levels.push_back({x, y, width, height, chunks(width, t.width), chunks(height, t.height)});
        }
    return levels;
}

// Every entry of the line-offset table must point inside the file past the
// table, at the chunk of its own rows (or tile), whose claimed size fits in
// what is left of the file and in its pixels uncompressed; no two chunks may overlap.
void check_chunks(FileBytes& file, const Layout& h, const std::string& where) {
    const bool tiled = h.tiles.width > 0;
    const std::int64_t rows = h.rows_per_chunk;
    const std::int64_t largest = std::min(rows, h.height) * h.width * h.bytes_per_pixel;
    if (!tiled && largest > kMaxChunkBytes)
        throw Error(where, "an EXR pixel chunk of " + std::to_string(std::min(rows, h.height)) + " rows of " +
                               std::to_string(h.width) + " pixels of " + std::to_string(h.bytes_per_pixel) +
                               " bytes is past the reader's limit of " + std::to_string(kMaxChunkBytes >> 20) + " MiB");
    const std::vector<Level> levels = levels_of(h);
    std::uint64_t chunks = 0;
    for (const Level& level : levels) chunks += static_cast<std::uint64_t>(level.columns * level.rows);
    const std::uint64_t table_end = h.header_end + 8 * chunks, size = file.size();
    if (table_end > size)
        throw Error(where,
                    "damaged EXR file: its line-offset table of " + std::to_string(chunks) + " entries is cut short");
    const std::vector<unsigned char> table = file.read(h.header_end, 8 * chunks);
    // A chunk starts with its first row, or its tile's column, row and level; then its size.
    const std::size_t head_size = tiled ? 20 : 8;
    std::vector<std::pair<std::uint64_t, std::uint64_t>> extents;  // each chunk's first and past-last byte
    std::uint64_t k = 0;
    for (const Level& level : levels)
        for (std::int64_t row = 0; row < level.rows; ++row)
            for (std::int64_t column = 0; column < level.columns; ++column, ++k) {
                const auto chunk = [k] { return "damaged EXR file: pixel chunk " + std::to_string(k); };
                const std::uint64_t offset = little_endian(table, static_cast<std::size_t>(8 * k), 8);
                if (offset < table_end || offset > size - head_size)  // size >= table_end > 20
                    throw Error(where, chunk() + " is at byte " + std::to_string(offset) +
                                           ", outside the pixel data (bytes " + std::to_string(table_end) + " to " +
                                           std::to_string(size) + ")");
                const std::vector<unsigned char> head = file.read(offset, head_size);
                const std::int64_t chunk_rows = std::min(rows, level.height - row * rows);
                const std::int64_t chunk_columns =
                    tiled ? std::min(h.tiles.width, level.width - column * h.tiles.width) : level.width;
                if (!tiled) {
                    const std::int64_t y = i32(head, 0), first_row = h.min_y + row * rows;
                    if (y != first_row)
                        throw Error(where, chunk() + " starts at row " + std::to_string(y) + ", not " +
                                               std::to_string(first_row));
                } else if (i32(head, 0) != column || i32(head, 4) != row || i32(head, 8) != level.x ||
                           i32(head, 12) != level.y) {
                    const auto tile = [](std::int64_t x, std::int64_t y, std::int64_t lx, std::int64_t ly) {
                        return "tile (" + std::to_string(x) + ", " + std::to_string(y) + ") of level (" +
                               std::to_string(lx) + ", " + std::to_string(ly) + ")";
                    };
                    throw Error(where, chunk() + " is " +
                                           tile(i32(head, 0), i32(head, 4), i32(head, 8), i32(head, 12)) + ", not " +
                                           tile(column, row, level.x, level.y));
                }
                const std::int64_t claimed = i32(head, head_size - 4);
                const std::uint64_t left = size - offset - head_size;
                const std::int64_t most = chunk_rows * chunk_columns * h.bytes_per_pixel;
                if (claimed < 0)
                    throw Error(where, chunk() + " claims a negative size (" + std::to_string(claimed) + " bytes)");
                if (static_cast<std::uint64_t>(claimed) > left)
                    throw Error(where, chunk() + " claims " + std::to_string(claimed) + " bytes, more than the " +
                                           std::to_string(left) + " left in the file");
                if (claimed > most) {
                    const std::string pixels =
                        tiled ? std::to_string(chunk_columns) + "×" + std::to_string(chunk_rows) + " pixels"
                              : std::to_string(chunk_rows) + " rows";
                    throw Error(where, chunk() + " claims " + std::to_string(claimed) + " bytes, more than its " +
                                           pixels + " hold uncompressed (" + std::to_string(most) + ")");
                }
                extents.emplace_back(offset, offset + head_size + static_cast<std::uint64_t>(claimed));
            }
    std::sort(extents.begin(), extents.end());
    for (std::size_t i = 1; i < extents.size(); ++i)
        if (extents[i].first < extents[i - 1].second)
            throw Error(where, "damaged EXR file: the pixel chunks at bytes " + std::to_string(extents[i - 1].first) +
                                   " and " + std::to_string(extents[i].first) + " overlap");
}

}  // namespace

int check_exr_file(const std::filesystem::path& path, const std::string& where) {
    FileBytes file(path, where);
    const Layout layout = walk_header(file, where);
    check_chunks(file, layout, where);
    return static_cast<int>(layout.rows_per_chunk);
}

}  // namespace sombra
