// Non-local-means weights (Buades et al. 2005) with the variance-aware patch
// distance of Rousselle, Knaus and Zwicker (2012) that NFOR uses: how much a
// pixel q's value may stand in for pixel p's, judged by how alike the
// patches around them are in a guide image, in units of the guide's noise.
#pragma once

#include <atomic>
#include <vector>

#include "denoise/raster.h"

namespace sombra {

struct NlMeansParams {
    int window_radius = 9;  // q within ±window_radius of p in x and y
    int patch_radius = 3;   // patches of (2·patch_radius + 1)² pixels
    float k = 0.5f;         // larger: neighbours' differences count for less, more blur
};

inline int window_side(const NlMeansParams& params) { return 2 * params.window_radius + 1; }
inline int window_offsets(const NlMeansParams& params) { return window_side(params) * window_side(params); }

// The centres x0 + stride·i < x1 and y0 + stride·j < y1 of `rect`: how
// many there are along x and in all.
inline int strided_count(int size, int stride) { return (size + stride - 1) / stride; }

// The weights of every pixel p among the strided centres of `centres`
// against every q = p + (dx, dy) of its window, in [0, 1], 0 where q is
// outside the image: weights[c · (2R + 1)² + o], c = j·n + i for the n
// centres along x, o = (dy + R)·(2R + 1) + (dx + R): one pixel's window
// is contiguous, as the regression reads it. `guide_variance` holds the
// variance of each guide value (same channel count). `scratch` is reused
// between calls to spare allocations.
void nl_means_tile_weights(const Raster& guide, const Raster& guide_variance, PixelRect centres, int stride,
                           const NlMeansParams& params, std::vector<float>& weights, std::vector<float>& scratch);

// The most channels nl_means_filter takes (colours, the feature groups,
// three colours' error estimates).
inline constexpr int kMaxFilterChannels = 9;

// Each pixel of `values` (at most kMaxFilterChannels channels; more throws
// std::invalid_argument) replaced by the weighted mean of its window's,
// weighted as above by `guide`; the same bytes for any `threads` (0 = all).
// Tiles not yet begun once `*cancel` is true are left 0.
Raster nl_means_filter(const Raster& values, const Raster& guide, const Raster& guide_variance,
                       const NlMeansParams& params, int threads, const std::atomic<bool>* cancel = nullptr);

}  // namespace sombra
