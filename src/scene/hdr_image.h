// High-dynamic-range images as the environment map (spec §10) needs them:
// linear RGB floats, every one finite and non-negative. Reading them from
// OpenEXR or Radiance .hdr files is io/'s (io/images/hdr_image.h).
#pragma once

#include <vector>

namespace sombra {

// A linear RGB image. Pixel (x, y) is column x = 0 … width−1 from the left,
// row y = 0 … height−1 from the top; its red, green and blue lie at
// rgb[3·(y·width + x) + 0, 1, 2]. An empty image (0 × 0, no floats) is what a
// default-constructed one holds; a reader never returns one.
struct HdrImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  // row-major, top row first, 3 floats per pixel, linear
};

}  // namespace sombra
