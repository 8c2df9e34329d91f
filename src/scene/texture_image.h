// Private to the texture decoder (texture_image.cpp): checks made on an
// image's bytes before stb_image reads them.
#pragma once

#include <span>
#include <string>

namespace sombra {

// "" unless the JPEG `bytes` hold a Huffman table that stb_image would read
// past its arrays (code counts adding up to more than 256): then what is wrong.
std::string jpeg_huffman_problem(std::span<const unsigned char> bytes);

}  // namespace sombra
