// Decoding texture images: PNG, TGA and BMP through stb_image (Debian's
// libstb), JPEG through libjpeg-turbo (texture_jpeg.cpp), WebP through
// libwebp (texture_webp.cpp), EXR and Radiance HDR through read_hdr_image. The format is told
// by the content's first bytes, the size read from the header and checked
// before any pixel is decoded, and the decoder reads through callbacks that
// notice when it wants bytes beyond the end (a truncated file; stb would
// quietly read zeros).
#include "io/images/texture_image.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <fstream>
#include <memory>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/image_limits.h"
#include "io/images/hdr_image.h"
#include "io/images/stb_guards.h"
#include "io/images/texture_jpeg.h"
#include "io/images/texture_webp.h"
#include "scene/texture.h"

namespace sombra {

namespace {

namespace fs = std::filesystem;

enum class Format { Png, Jpeg, Bmp, Tga, Webp, Unsupported };

struct Sniffed {
    Format format;
    const char* name;  // for messages: what the bytes are
};

bool starts_with(std::span<const unsigned char> bytes, std::string_view magic) {
    return bytes.size() >= magic.size() && std::memcmp(bytes.data(), magic.data(), magic.size()) == 0;
}

// What the bytes hold, by their signature. TGA has none: whatever carries no
// other format's signature is given to stb's TGA reader, which checks the header.
Sniffed sniff(std::span<const unsigned char> bytes) {
    if (starts_with(bytes, "\x89PNG\r\n\x1a\n")) return {Format::Png, "PNG"};
    // 0xff fill bytes may come before the start-of-image marker (decode_jpeg skips them).
    std::size_t fill = 0;
    while (fill < bytes.size() && bytes[fill] == 0xff) ++fill;
    if (fill > 0 && fill < bytes.size() && bytes[fill] == 0xd8) return {Format::Jpeg, "JPEG"};
    if (starts_with(bytes, "BM")) return {Format::Bmp, "BMP"};
    if (bytes.size() >= 12 && starts_with(bytes, "RIFF") && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0)
        return {Format::Webp, "WebP"};
    // Formats stb would read too, but spec §12 does not list: refused by name.
    if (starts_with(bytes, "GIF8")) return {Format::Unsupported, "a GIF image"};
    if (starts_with(bytes, "8BPS")) return {Format::Unsupported, "a Photoshop (PSD) image"};
    if (starts_with(bytes, "\x53\x80\xf6\x34")) return {Format::Unsupported, "a Softimage PIC image"};
    if (starts_with(bytes, "P5") || starts_with(bytes, "P6")) return {Format::Unsupported, "a PNM image"};
    if (starts_with(bytes, "#?")) return {Format::Unsupported, "a Radiance HDR image (name it .hdr)"};
    if (starts_with(bytes, "\x76\x2f\x31\x01")) return {Format::Unsupported, "an OpenEXR image (name it .exr)"};
    return {Format::Tga, "TGA"};
}

// stb reads through these callbacks rather than from memory directly so that
// a request beyond the last byte is seen: stb would otherwise read zeros there
// and return an image whose end is black. stb asks for more only when it needs
// a byte, so a complete file never gets to the end of its bytes and asks again.
struct MemorySource {
    std::span<const unsigned char> bytes;
    std::size_t at = 0;
    bool wanted_more = false;  // a read or skip went past the end
};

int source_read(void* user, char* data, int size) {
    auto* s = static_cast<MemorySource*>(user);
    if (size <= 0) return 0;
    const std::size_t n = std::min(static_cast<std::size_t>(size), s->bytes.size() - s->at);
    if (n == 0) s->wanted_more = true;
    std::memcpy(data, s->bytes.data() + s->at, n);
    s->at += n;
    return static_cast<int>(n);
}
void source_skip(void* user, int n) {
    auto* s = static_cast<MemorySource*>(user);
    const std::size_t left = s->bytes.size() - s->at;
    if (n > 0 && static_cast<std::size_t>(n) > left) s->wanted_more = true;
    s->at += n > 0 ? std::min(static_cast<std::size_t>(n), left) : 0;
}
int source_eof(void* user) {
    const auto* s = static_cast<const MemorySource*>(user);
    return s->at >= s->bytes.size() ? 1 : 0;
}
constexpr stbi_io_callbacks kCallbacks{&source_read, &source_skip, &source_eof};

// One stored value in [0, 1] as the encoding wants it: colour channels (not
// alpha, the last of 2 or 4) through the sRGB curve.
bool is_colour_channel(TextureEncoding encoding, int channel, int channels) {
    const bool alpha = (channels == 2 || channels == 4) && channel == channels - 1;
    return encoding == TextureEncoding::Color && !alpha;
}

// A one-line reason from stb ("Corrupt PNG", "bad huffman code"...).
std::string stb_reason() {
    const char* reason = stbi_failure_reason();
    if (!reason) return "unknown reason";
    if (std::string_view(reason) == "outofdata") return "the data ends too early (truncated?)";
    return reason;
}

// Decoded pixels (8 or 16 bits per value, `channels` interleaved, rows top
// to bottom) as a Texture of floats in [0, 1], colour channels sRGB-decoded
// when `encoding` says so.
Texture texture_from_pixels(const void* pixels, bool sixteen, int width, int height, int channels,
                            TextureEncoding encoding, const std::string& where) {
    Texture t;
    t.source = where;
    t.encoding = encoding;
    t.width = width;
    t.height = height;
    t.channels = channels;
    const std::size_t count =
        static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(channels);
    t.texels.resize(count);
    // Each channel's values through a table built once: the value for code c
    // is the formula's (srgb_decode, or c/max), so the floats are the same as
    // evaluating it per value, at a table look-up's cost instead of a pow. A
    // 16-bit image with fewer values than its table has entries gets none.
    const auto fill = [&](const auto* v, unsigned max_code) {
        if (count <= max_code) {
            for (std::size_t i = 0; i < count; ++i)
                t.texels[i] =
                    is_colour_channel(encoding, static_cast<int>(i % static_cast<std::size_t>(channels)), channels)
                        ? srgb_decode(v[i], max_code)
                        : static_cast<float>(v[i]) / static_cast<float>(max_code);
            return;
        }
        std::vector<float> data(max_code + 1), colour;
        for (unsigned c = 0; c <= max_code; ++c) data[c] = static_cast<float>(c) / static_cast<float>(max_code);
        std::array<const float*, 4> table_of{};
        for (int c = 0; c < channels; ++c) {
            if (!is_colour_channel(encoding, c, channels)) {
                table_of[static_cast<std::size_t>(c)] = data.data();
                continue;
            }
            if (colour.empty()) {
                colour.resize(max_code + 1);
                for (unsigned code = 0; code <= max_code; ++code) colour[code] = srgb_decode(code, max_code);
            }
            table_of[static_cast<std::size_t>(c)] = colour.data();
        }
        const auto n = static_cast<std::size_t>(channels);
        for (std::size_t i = 0; i < count; i += n)
            for (std::size_t c = 0; c < n; ++c) t.texels[i + c] = table_of[c][v[i + c]];
    };
    if (sixteen)
        fill(static_cast<const std::uint16_t*>(pixels), 65535);
    else
        fill(static_cast<const unsigned char*>(pixels), 255);
    return t;
}

Texture decode_stb(std::span<const unsigned char> bytes, Format format, const char* format_name,
                   TextureEncoding encoding, const std::string& where) {
    if (format == Format::Png)
        if (const std::string problem = png_chunk_problem(bytes); !problem.empty()) throw Error(where, problem);
    std::optional<std::vector<unsigned char>> mended;
    if (format == Format::Png && (mended = png_without_leading_empty_idat(bytes))) bytes = *mended;
    MemorySource source{bytes};
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_callbacks(&kCallbacks, &source, &width, &height, &channels))
        throw Error(where, std::string("cannot read the ") + format_name + " header: " + stb_reason());
    if (channels < 1 || channels > 4)
        throw Error(where, "image has " + std::to_string(channels) + " channels (expected 1 to 4)");
    check_texture_size(where, width, height, channels);
    source = MemorySource{bytes};
    const bool sixteen = format == Format::Png && stbi_is_16_bit_from_callbacks(&kCallbacks, &source);

    source = MemorySource{bytes};
    int got_width = 0, got_height = 0, got_channels = 0;
    void* pixels = sixteen ? static_cast<void*>(stbi_load_16_from_callbacks(&kCallbacks, &source, &got_width,
                                                                            &got_height, &got_channels, channels))
                           : static_cast<void*>(stbi_load_from_callbacks(&kCallbacks, &source, &got_width, &got_height,
                                                                         &got_channels, channels));
    if (!pixels) throw Error(where, std::string("cannot decode as ") + format_name + ": " + stb_reason());
    const std::unique_ptr<void, void (*)(void*)> owner(pixels, &stbi_image_free);
    if (source.wanted_more) throw Error(where, std::string(format_name) + " file is truncated");
    if (got_width != width || got_height != height)
        throw Error(where, std::string(format_name) + " image decoded to another size than its header gives");

    return texture_from_pixels(pixels, sixteen, width, height, channels, encoding, where);
}

std::string lowercase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

}  // namespace

void check_texture_size(const std::string& where, std::int64_t width, std::int64_t height, std::int64_t channels) {
    if (width < 1 || height < 1)
        throw Error(where, "image has no pixels (" + std::to_string(width) + "×" + std::to_string(height) + ")");
    if (width > kMaxImageSide || height > kMaxImageSide || width * height * channels > kMaxTextureValues)
        throw Error(where, "image is " + std::to_string(width) + "×" + std::to_string(height) + " pixels of " +
                               std::to_string(channels) + " channels, more than the limit of " +
                               std::to_string(kMaxImageSide) + " per side and " + std::to_string(kMaxTextureValues) +
                               " values in all");
}

Texture decode_texture(std::span<const unsigned char> bytes, TextureEncoding encoding, const std::string& source) {
    if (bytes.empty()) throw Error(source, "image file is empty");
    const Sniffed kind = sniff(bytes);
    if (kind.format == Format::Unsupported)
        throw Error(source, std::string("unsupported image format: ") + kind.name +
                                " (supported: PNG, JPEG, TGA, BMP, WebP, .exr, .hdr)");
    if (kind.format == Format::Webp || kind.format == Format::Jpeg) {
        const DecodedPixels image =
            kind.format == Format::Webp ? decode_webp(bytes, source) : decode_jpeg(bytes, source);
        return texture_from_pixels(image.pixels.data(), false, image.width, image.height, image.channels, encoding,
                                   source);
    }
    return decode_stb(bytes, kind.format, kind.name, encoding, source);
}

Texture read_texture_file(const fs::path& path, TextureEncoding encoding) {
    const std::string where = path.string();
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw Error(where, "no such file");
    if (fs::is_directory(status)) throw Error(where, "is a folder, not an image");
    if (!fs::is_regular_file(status)) throw Error(where, "is not a regular file");

    const std::string extension = lowercase(path.extension().string());
    if (extension == ".exr" || extension == ".hdr") {
        HdrImage image = read_hdr_image(path);  // linear whatever the encoding; its errors name the file
        Texture t;
        t.source = where;
        t.encoding = encoding;
        t.width = image.width;
        t.height = image.height;
        t.channels = 3;
        t.texels = std::move(image.rgb);
        return t;
    }

    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw Error(where, "cannot read the file's size");
    if (size > kMaxTextureFileBytes)
        throw Error(where, "image file is larger than " + std::to_string(kMaxTextureFileBytes >> 20) + " MiB");
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(where, "cannot open: permission denied or unreadable");
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (static_cast<std::size_t>(in.gcount()) != bytes.size()) throw Error(where, "cannot read the whole file");
    return decode_texture(bytes, encoding, where);
}

}  // namespace sombra
