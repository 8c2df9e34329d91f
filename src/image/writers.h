// The three image encoders behind write_image. Each writes the whole file at
// `file` directly (write_image makes that a temporary file) and throws on any
// failure. Pixels with a non-finite channel are written as black in every
// format, so a stray NaN never reaches a viewer or a downstream tool.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

#include "image/image_io.h"

namespace sombra {

// 8-bit sRGB code of one linear channel value already scaled by exposure:
// the exact piecewise sRGB transfer function, clamped to [0, 1], rounded to nearest.
std::uint8_t encode_srgb8(float linear);

// 8-bit RGB PNG with an sRGB chunk (plus the matching gAMA and cHRM).
void write_png(const std::filesystem::path& file, ImageView image, DisplayTransform display);

// The JPEG format's largest side (libjpeg's JPEG_MAX_DIMENSION).
inline constexpr int kMaxJpegSide = 65500;

// Baseline JPEG, 8-bit sRGB (JFIF), quality 95.
void write_jpeg(const std::filesystem::path& file, ImageView image, DisplayTransform display);

// Portable float map: "PF\n<w> <h>\n-1.0\n", then little-endian float32 RGB,
// rows bottom to top (the PFM convention). Linear radiance.
void write_pfm(const std::filesystem::path& file, ImageView image);

// OpenEXR with 32-bit float R, G, B channels and `layers`, ZIP compressed. Linear radiance.
void write_exr(const std::filesystem::path& file, ImageView image, std::span<const ImageChannel> layers,
               std::span<const ImageAttribute> attributes = {});

// True when all three channels of pixel `index` are finite.
inline bool pixel_is_finite(const float* rgb, std::size_t index) {
    const float* p = rgb + 3 * index;
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// A C stream opened by open_for_writing; closed at most once.
struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using OutputFile = std::unique_ptr<std::FILE, FileCloser>;

// Opens `file` for binary writing; throws std::system_error on failure.
inline OutputFile open_for_writing(const std::filesystem::path& file) {
    std::FILE* stream = std::fopen(file.c_str(), "wb");
    if (stream == nullptr) throw std::system_error(errno, std::generic_category());
    return OutputFile(stream);
}

// Flushes and closes `file`, throwing std::system_error if any write on it failed.
inline void finish_writing(OutputFile file) {
    const bool flushed = std::fflush(file.get()) == 0 && std::ferror(file.get()) == 0;
    const int flush_errno = errno;
    const bool closed = std::fclose(file.release()) == 0;
    if (!flushed) throw std::system_error(flush_errno != 0 ? flush_errno : EIO, std::generic_category());
    if (!closed) throw std::system_error(errno, std::generic_category());
}

}  // namespace sombra
