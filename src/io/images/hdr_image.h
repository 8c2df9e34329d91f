// Reading high-dynamic-range images (spec §10; §12 for EXR and HDR
// textures): OpenEXR through image/'s checked reader, Radiance .hdr through
// stb_image, into the model's HdrImage (scene/hdr_image.h), checked so that
// the renderer can trust every pixel.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "scene/hdr_image.h"

namespace sombra {

// Reads an OpenEXR (.exr) or Radiance (.hdr) file; the extension, in any
// case, decides which. EXR: the R, G and B channels (a missing one reads as
// 0), or a single Y channel as grey; the data window becomes the image (its
// top-left corner is pixel (0, 0)), a tiled file's first level; read by
// image/'s read_exr_channels, which refuses multi-part and deep files and
// any whose layout claims more than the file holds (image/exr_check.h).
// HDR: stb_image's decoder (RLE or flat RGBE scanlines, "-Y H +X W" layout).
//
// Throws Error(path, what) when the file is missing or unreadable, is not
// that format (or is truncated), has another extension, has no pixels or more
// than kMaxImageSide per side or kMaxPixels in all (core/image_limits.h;
// checked from the header, before the pixels are allocated), or holds a
// negative, NaN or infinite value: the message names the first such pixel in
// reading order, e.g. "pixel (3, 7) is negative (-0.25)".
HdrImage read_hdr_image(const std::filesystem::path& path);

// How read_hdr_image treats negative values. NaN and infinity are errors whatever these say.
struct HdrReadOptions {
    // Read negative values as 0 instead of failing (resampled maps often ring
    // slightly below 0); the count of values so read is returned.
    bool clamp_negative = false;
    // Appended to the "is negative" message when clamp_negative is off, e.g.
    // the way to opt in ("; add ... to read negative values as 0").
    std::string negative_hint;
};

// read_hdr_image with options; `clamped_values`, when given, receives the
// number of channel values read as 0 (always 0 unless clamp_negative).
HdrImage read_hdr_image(const std::filesystem::path& path, const HdrReadOptions& options,
                        std::size_t* clamped_values = nullptr);

}  // namespace sombra
