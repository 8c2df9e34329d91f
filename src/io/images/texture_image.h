// Decoding texture images (spec §12) into the model's Texture
// (scene/texture.h): PNG, JPEG, TGA and BMP through stb_image behind the
// guards of stb_guards.h, WebP through libwebp, EXR and Radiance HDR through read_hdr_image. What
// every reader with material textures calls (OBJ's MTL, scene files, glTF).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "scene/texture.h"

namespace sombra {

// The most values (width × height × channels) one texture may hold: 1 GiB of
// floats. Checked from the image's header, before any pixel is decoded.
inline constexpr std::int64_t kMaxTextureValues = std::int64_t{1} << 28;
// The largest image file read (its encoded bytes, all in memory at once).
inline constexpr std::uintmax_t kMaxTextureFileBytes = std::uintmax_t{1} << 30;

// Reads an image file: PNG (8 or 16 bit), JPEG, TGA, BMP or WebP, recognised by
// their content whatever the extension; .exr (OpenEXR) and .hdr (Radiance)
// by extension, through read_hdr_image (io/images/hdr_image.h), as 3-channel
// linear RGB. Throws Error(path, what) with a one-line message for a missing
// or unreadable file, another format, a truncated or corrupt image, or one
// larger than kMaxImageSide per side (core/image_limits.h) or kMaxTextureValues.
Texture read_texture_file(const std::filesystem::path& path, TextureEncoding encoding);

// Throws Error(where, what) unless width × height pixels of `channels`
// values fit the limits above (and are at least 1 × 1): what every decoder
// checks from the header, before it allocates the pixels.
void check_texture_size(const std::string& where, std::int64_t width, std::int64_t height, std::int64_t channels);

// Decodes an encoded PNG, JPEG, TGA, BMP or WebP image held in memory; errors as
// read_texture_file's, Error(source, what). The result's source is `source`.
Texture decode_texture(std::span<const unsigned char> bytes, TextureEncoding encoding, const std::string& source);

}  // namespace sombra
