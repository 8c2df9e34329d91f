// 8-bit pixels as a decoder other than stb_image hands them to
// texture_image.cpp, which turns them into a Texture.
#pragma once

#include <vector>

namespace sombra {

struct DecodedPixels {
    int width = 0, height = 0;
    int channels = 0;                   // 1 (grey), 3 (RGB) or 4 (RGBA)
    std::vector<unsigned char> pixels;  // rows top to bottom, channels interleaved, 8 bits each
};

}  // namespace sombra
