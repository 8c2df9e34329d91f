// WebP images (EXT_texture_webp, spec §24) through libwebp (Debian's
// libwebp-dev): the pixels texture_image.cpp turns into a Texture.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace sombra {

struct WebpPixels {
    int width = 0, height = 0;
    int channels = 0;                   // 3 (RGB), or 4 when the image has alpha
    std::vector<unsigned char> pixels;  // rows top to bottom, channels interleaved, 8 bits each
};

// Decodes a still WebP image, lossy or lossless. Its size is read from the
// header and checked (check_texture_size) before the pixels are allocated.
// Throws Error(where, what) for bytes that are no WebP image, an animation,
// a size beyond the limits, or data that does not decode (truncated, corrupt).
WebpPixels decode_webp(std::span<const unsigned char> bytes, const std::string& where);

}  // namespace sombra
