// NFOR's core (Bitterli et al. 2016, §4): for pixels p on a grid of every
// second row and column (and any pixel the grid leaves with little
// weight), a first-order weighted least-squares fit of the target colour
// to the features over p's window, weighted by non-local means on a guide
// image; the fit then predicts every pixel of the window, and each
// pixel's output is the weighted mean of the predictions of all windows
// that hold it ("collaborative"). The output is linear in the target with weights that
// depend on the guide and features only, so it can be run backwards
// (the adjoint) to give one pixel's weights over the target.
#pragma once

#include <atomic>
#include <vector>

#include "denoise/nl_means.h"
#include "denoise/raster.h"

namespace sombra {

// The features a fit reads beside the pixel's position in the window:
// albedo (3), normal (3), depth (1).
inline constexpr int kRegressionFeatures = 7;

// A ridge of kRegressionRidge · Σw on every column but the constant one
// keeps a fit well posed where features are collinear; the constant column,
// left free, makes every pixel's weights add up to 1. Small enough that a
// colour the features explain exactly passes through to float rounding (a
// ridge of 10⁻³ blurred such colours by about 10⁻⁴, and measured no better).
inline constexpr double kRegressionRidge = 1e-6;

struct RegressionResult {
    Raster value;       // 3 channels
    Raster weight_sum;  // 1 channel: Σ over the windows holding the pixel of its weight in them (≥ 1)
    // 1 where the pixel's own window was fitted besides the grid's (pixel
    // index): those the grid's windows left with little weight.
    std::vector<unsigned char> own_window;
};

// `target` and `guide` have 3 channels, `guide_variance` the variance of
// each guide value, `features` kRegressionFeatures channels. The same bytes
// for any `threads` (0 = all). Windows of tiles not yet begun once
// `*cancel` is true are left out: the result is then unfinished.
RegressionResult collaborative_regression(const Raster& target, const Raster& guide, const Raster& guide_variance,
                                          const Raster& features, const NlMeansParams& params, int threads,
                                          const std::atomic<bool>* cancel = nullptr);

// The adjoint of collaborative_regression with its weights held fixed:
// adds ∂(Σ_p g[p]·value[p]) / ∂target[q], per channel, to g_target[q] for
// every pixel q, given `g` (3 channels) that is zero outside `support`
// and the forward run's result.
void collaborative_regression_adjoint(const Raster& guide, const Raster& guide_variance, const Raster& features,
                                      const NlMeansParams& params, const RegressionResult& forward, const Raster& g,
                                      PixelRect support, Raster& g_target);

}  // namespace sombra
