// Private to the texture decoder (texture_image.cpp): checks made on an
// image's bytes before stb_image reads them (texture_jpeg_check.cpp,
// texture_png_check.cpp), against faults of stb_image found by fuzzing.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sombra {

// "" unless the JPEG `bytes` hold a Huffman table that stb_image would read
// past its arrays (code counts adding up to more than 256): then what is wrong.
std::string jpeg_huffman_problem(std::span<const unsigned char> bytes);

// The PNG `bytes` without the empty IDAT chunks that come before its first
// IDAT with data (stb_image would memcpy zero bytes to a null buffer for
// them); nullopt when there is none, the usual case, so nothing is copied.
std::optional<std::vector<unsigned char>> png_without_leading_empty_idat(std::span<const unsigned char> bytes);

}  // namespace sombra
