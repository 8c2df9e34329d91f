// JPEG images through libjpeg-turbo (Debian's libjpeg62-turbo): the pixels
// texture_image.cpp turns into a Texture. stb_image read them until fuzzing
// found its JPEG decoder reading Huffman tables a file never defined
// (docs/robustness.md); libjpeg-turbo is fuzzed upstream and already linked
// for JPEG output.
#pragma once

#include <span>
#include <string>

#include "io/images/decoded_pixels.h"

namespace sombra {

// The most scans a progressive JPEG may have: real encoders write about ten;
// each scan costs a pass over the whole image, so a small file of many empty
// scans would otherwise take minutes.
inline constexpr int kMaxJpegScans = 256;

// Decodes a baseline, progressive or arithmetic-coded JPEG to grey (one
// channel) or RGB (three; CMYK files are converted, Adobe's inverted CMYK
// when the file carries Adobe's marker). The size is read from the header
// and checked (check_texture_size) before any pixel is decoded. Throws
// Error(where, what) for a file that ends before its end-of-image marker
// ("JPEG file is truncated"), corrupt entropy-coded data (wrong pixels, not a warning), too
// many scans, or anything libjpeg refuses, with libjpeg's reason.
DecodedPixels decode_jpeg(std::span<const unsigned char> bytes, const std::string& where);

}  // namespace sombra
