#include "io/images/hdr_image.h"

#include <stb_image.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "core/error.h"
#include "core/format.h"
#include "core/image_limits.h"
#include "image/image_io.h"

namespace sombra {

namespace {

std::string lowercase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// The size limits of core/image_limits.h, checked before any pixel is allocated.
void check_size(const std::filesystem::path& path, std::int64_t width, std::int64_t height) {
    if (width < 1 || height < 1)
        throw Error(path.string(),
                    "image has no pixels (" + std::to_string(width) + "×" + std::to_string(height) + ")");
    if (width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxPixels)
        throw Error(path.string(), "image is " + std::to_string(width) + "×" + std::to_string(height) +
                                       " pixels, more than the limit of " + std::to_string(kMaxImageSide) +
                                       " per side and " + std::to_string(kMaxPixels) + " in all");
}

// The first NaN or infinite value, in reading order, is an error; so is the
// first negative one, unless the options read negatives as 0. Returns how many
// values were read as 0.
std::size_t check_pixels(const std::filesystem::path& path, HdrImage& image, const HdrReadOptions& options) {
    const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    std::size_t clamped = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
        std::string problem;
        for (std::size_t c = 0; c < 3 && problem.empty(); ++c) {
            float& v = image.rgb[3 * p + c];
            if (std::isnan(v))
                problem = "NaN";
            else if (std::isinf(v))
                problem = "infinite";
            else if (v < 0.0f && options.clamp_negative) {
                v = 0.0f;
                ++clamped;
            } else if (v < 0.0f)
                problem = "negative (" + format_number(v) + ")" + options.negative_hint;
        }
        if (!problem.empty()) {
            const auto x = p % static_cast<std::size_t>(image.width);
            const auto y = p / static_cast<std::size_t>(image.width);
            throw Error(path.string(), "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is " + problem);
        }
    }
    return clamped;
}

// Through image/'s EXR reader, which checks the file's layout before OpenEXR
// allocates what the file claims.
HdrImage read_exr(const std::filesystem::path& path) {
    const ExrChannels exr = read_exr_channels(path, {"R", "G", "B", "Y"});
    const auto channel = [&](const char* name) -> const std::vector<float>* {
        const auto it = std::find(exr.names.begin(), exr.names.end(), name);
        return it == exr.names.end() ? nullptr : &exr.values[static_cast<std::size_t>(it - exr.names.begin())];
    };
    const std::vector<float>* rgb[3] = {channel("R"), channel("G"), channel("B")};
    const std::vector<float>* y = channel("Y");
    const bool has_rgb = rgb[0] || rgb[1] || rgb[2];
    if (!has_rgb && !y) throw Error(path.string(), "OpenEXR file has no R, G, B or Y channel");
    HdrImage image;
    image.width = exr.width;
    image.height = exr.height;
    const std::size_t pixels = static_cast<std::size_t>(exr.width) * static_cast<std::size_t>(exr.height);
    image.rgb.assign(pixels * 3, 0.0f);
    for (std::size_t c = 0; c < 3; ++c) {
        const std::vector<float>* from = has_rgb ? rgb[c] : y;  // a missing colour channel reads as 0; Y alone as grey
        if (from)
            for (std::size_t p = 0; p < pixels; ++p) image.rgb[3 * p + c] = (*from)[p];
    }
    return image;
}

// stb_image reads through these callbacks, for two reasons.
// - A truncated file must be noticed: stb treats the bytes past the end as
//   zeros. stb asks for more bytes than are left only when it needs them,
//   except when it refills its own 128-byte buffer, which may legitimately
//   end at the end of the file.
// - Debian's stb (2022-09) loops forever on a run-length count of 0 at the end
//   of the data, where it reads zeros. So past the end the source reports no
//   end of file but yields '\n' bytes: every loop of stb's Radiance reader
//   then makes progress (a header token ends, a run-length count is 10), and
//   whatever it decodes is thrown away because the file came up short.
struct StbSource {
    std::FILE* file = nullptr;
    bool came_up_short = false;  // a read found no byte, or fewer than a pixel needed
};
constexpr int kStbBufferSize = 128;  // sizeof stbi__context::buffer_start

int stb_read(void* user, char* data, int size) {
    auto* source = static_cast<StbSource*>(user);
    if (size <= 0) return 0;
    const std::size_t got = std::fread(data, 1, static_cast<std::size_t>(size), source->file);
    if (got > 0) {
        if (got < static_cast<std::size_t>(size) && size < kStbBufferSize) source->came_up_short = true;
        return static_cast<int>(got);
    }
    source->came_up_short = true;
    std::fill(data, data + size, '\n');
    return size;
}
void stb_skip(void* user, int n) {
    auto* source = static_cast<StbSource*>(user);
    if (std::fseek(source->file, n, SEEK_CUR) != 0) source->came_up_short = true;
}
int stb_eof(void*) { return 0; }  // see StbSource

HdrImage read_radiance(const std::filesystem::path& path) {
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw Error(path.string(), "cannot open");
    StbSource source{file.get()};
    const stbi_io_callbacks callbacks{&stb_read, &stb_skip, &stb_eof};
    const auto restart = [&] {
        std::rewind(source.file);
        source.came_up_short = false;
    };

    if (!stbi_is_hdr_from_callbacks(&callbacks, &source))
        throw Error(path.string(), "not a Radiance HDR file (it must start with #?RADIANCE or #?RGBE)");
    restart();
    int width = 0, height = 0, components = 0;
    if (!stbi_info_from_callbacks(&callbacks, &source, &width, &height, &components))
        throw Error(path.string(), std::string("cannot read the Radiance header: ") + stbi_failure_reason());
    check_size(path, width, height);

    restart();
    float* pixels = stbi_loadf_from_callbacks(&callbacks, &source, &width, &height, &components, 3);
    if (!pixels) throw Error(path.string(), std::string("cannot read as Radiance HDR: ") + stbi_failure_reason());
    const std::unique_ptr<float, void (*)(void*)> owner(pixels, &stbi_image_free);
    if (source.came_up_short || std::ferror(source.file)) throw Error(path.string(), "Radiance HDR file is truncated");
    check_size(path, width, height);  // the same header, read again: the same size

    HdrImage image;
    image.width = width;
    image.height = height;
    image.rgb.assign(pixels, pixels + static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
    return image;
}

}  // namespace

HdrImage read_hdr_image(const std::filesystem::path& path) { return read_hdr_image(path, HdrReadOptions{}); }

HdrImage read_hdr_image(const std::filesystem::path& path, const HdrReadOptions& options, std::size_t* clamped_values) {
    const std::string extension = lowercase(path.extension().string());
    if (extension != ".exr" && extension != ".hdr")
        throw Error(path.string(), "unsupported image format \"" + path.extension().string() +
                                       "\" (supported: .exr (OpenEXR), .hdr (Radiance))");
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(path.string(), "no such file");
    if (std::filesystem::is_directory(path, ec)) throw Error(path.string(), "is a folder, not an image");

    HdrImage image = extension == ".exr" ? read_exr(path) : read_radiance(path);
    const std::size_t clamped = check_pixels(path, image, options);
    if (clamped_values) *clamped_values = clamped;
    return image;
}

}  // namespace sombra
