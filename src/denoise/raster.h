// An image of `channels` floats a pixel, row-major, top row first: what the
// denoiser's stages read and write (colours, variances, features, weights).
#pragma once

#include <cstddef>
#include <vector>

namespace sombra {

struct Raster {
    int width = 0, height = 0, channels = 0;
    std::vector<float> values;

    Raster() = default;
    Raster(int w, int h, int c, float fill = 0.0f)
        : width(w),
          height(h),
          channels(c),
          values(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(c), fill) {}

    std::size_t pixel(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }
    float* at(int x, int y) { return &values[pixel(x, y) * static_cast<std::size_t>(channels)]; }
    const float* at(int x, int y) const { return &values[pixel(x, y) * static_cast<std::size_t>(channels)]; }
};

// A rectangle of pixels x0 ≤ x < x1, y0 ≤ y < y1.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// The denoiser works on tiles of kDenoiseTile × kDenoiseTile pixels: each
// is computed alone and in the same way whatever the thread count, so the
// result is the same bytes on any number of threads.
inline constexpr int kDenoiseTile = 32;

inline int tile_count(int size) { return (size + kDenoiseTile - 1) / kDenoiseTile; }
inline PixelRect tile_rect(int tx, int ty, int width, int height) {
    const int x0 = tx * kDenoiseTile, y0 = ty * kDenoiseTile;
    return {x0, y0, x0 + kDenoiseTile < width ? x0 + kDenoiseTile : width,
            y0 + kDenoiseTile < height ? y0 + kDenoiseTile : height};
}

}  // namespace sombra
