// Private to the texture decoder (texture_image.cpp): checks made on an
// image's bytes before stb_image reads them (texture_png_check.cpp), against
// faults of stb_image found by fuzzing.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sombra {

// "" unless an IDAT chunk of the PNG `bytes` claims more bytes than the file
// has left (stb would allocate that much before reading): then what is wrong.
std::string png_chunk_problem(std::span<const unsigned char> bytes);

// The PNG `bytes` without the empty IDAT chunks that come before its first
// IDAT with data (stb_image would memcpy zero bytes to a null buffer for
// them); nullopt when there is none, the usual case, so nothing is copied.
std::optional<std::vector<unsigned char>> png_without_leading_empty_idat(std::span<const unsigned char> bytes);

}  // namespace sombra
