// WebP images (EXT_texture_webp, spec §24) through libwebp (Debian's
// libwebp-dev): the pixels texture_image.cpp turns into a Texture.
#pragma once

#include <span>
#include <string>

#include "io/images/decoded_pixels.h"

namespace sombra {

// Decodes a still WebP image, lossy or lossless. Its size is read from the
// header and checked (check_texture_size) before the pixels are allocated.
// Throws Error(where, what) for bytes that are no WebP image, an animation,
// a size beyond the limits, or data that does not decode (truncated, corrupt).
// The pixels come as RGB, or RGBA when the image has alpha.
DecodedPixels decode_webp(std::span<const unsigned char> bytes, const std::string& where);

}  // namespace sombra
