// Synthetic denoiser inputs for the tests: random rasters, and a picture of
// two materials under a light gradient, its pixels the means of noisy samples.
#pragma once

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "denoise/denoise_layers.h"
#include "denoise/raster.h"

namespace sombra::test {

// A raster of uniform random values in [lo, hi), the same for a seed.
inline Raster random_raster(int w, int h, int channels, float lo, float hi, unsigned seed) {
    Raster r(w, h, channels);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    for (float& v : r.values) v = u(rng);
    return r;
}

// The noise-free radiance of pixel (x, y), channel c: an albedo that
// changes at x = width/2 times a smooth light.
inline float clean_radiance(int x, int y, int c, int width, int height) {
    const float albedo = x < width / 2 ? 0.2f + 0.3f * static_cast<float>(c) : 0.7f - 0.2f * static_cast<float>(c);
    const float light = 0.5f + 1.5f * static_cast<float>(x + y) / static_cast<float>(width + height);
    return albedo * light;
}

inline float clean_albedo(int x, int c, int width) {
    return x < width / 2 ? 0.2f + 0.3f * static_cast<float>(c) : 0.7f - 0.2f * static_cast<float>(c);
}

// Layers of `spp` samples a pixel, each the clean radiance times an
// exponential variate of mean 1 (so every mean is unbiased), the features
// noise-free; `noise` 0 gives the clean picture in both halves.
inline DenoiseLayers synthetic_layers(int width, int height, int spp, bool noise, unsigned seed = 7) {
    DenoiseLayers layers;
    layers.width = width;
    layers.height = height;
    const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    for (int h = 0; h < 2; ++h) {
        layers.color[h].assign(3 * n, 0.0f);
        layers.albedo[h].assign(3 * n, 0.0f);
        layers.normal[h].assign(3 * n, 0.0f);
        layers.depth[h].assign(n, 0.0f);
    }
    layers.variance.assign(3 * n, 0.0f);
    std::mt19937 rng(seed);
    std::exponential_distribution<double> variate(1.0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t p =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
            for (int c = 0; c < 3; ++c) {
                const double clean = clean_radiance(x, y, c, width, height);
                double sum[2] = {0, 0}, squares = 0, total = 0;
                for (int k = 0; k < spp; ++k) {
                    const double v = noise ? clean * variate(rng) : clean;
                    sum[k % 2] += v;
                    total += v;
                    squares += v * v;
                }
                const int half_count = spp / 2;  // spp is even here: both halves hold spp / 2 samples
                for (int h = 0; h < 2; ++h) layers.color[h][3 * p + c] = static_cast<float>(sum[h] / half_count);
                const double mean = total / spp;
                layers.variance[3 * p + c] =
                    static_cast<float>(std::max(0.0, squares - spp * mean * mean) / (spp - 1.0) / spp);
                for (int h = 0; h < 2; ++h) {
                    layers.albedo[h][3 * p + c] = clean_albedo(x, c, width);
                    layers.normal[h][3 * p + c] = c == 2 ? 1.0f : 0.0f;
                }
            }
            for (int h = 0; h < 2; ++h) layers.depth[h][p] = 3.0f + 0.01f * static_cast<float>(y);
        }
    return layers;
}

}  // namespace sombra::test
