#include "denoise/regression.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace sombra {

namespace {

// The design's columns: 1, the offset in x and in y, the features.
constexpr int kDesign = 3 + kRegressionFeatures;
using NormalMatrix = Eigen::Matrix<double, kDesign, kDesign>;
using Coefficients = Eigen::Matrix<double, kDesign, 3>;

// Windows are fitted on every second pixel along x and y: neighbouring
// windows' fits are nearly alike, and a pixel still lies in 64 windows of
// 15 × 15 (a quarter of the work; docs/performance.md, "The denoiser").
// A pixel the grid's windows give less than this total weight gets a
// window of its own as well, so that no pixel rests on a few weak fits.
constexpr int kCentreStride = 2;
constexpr float kOwnWindowBelow = 1.0f;
// One centre's non-local-means weights alone cost about 1/kOneCentreCost
// of a whole tile's: a tile with more own windows computes them all.
constexpr int kOneCentreCost = 10;

// A window whose pixels other than its centre weigh less than half the
// centre (weight 1) in all is fitted by its weighted mean: a first-order
// fit would lean on the centre alone, and it costs ten times as much.
constexpr double kFirstOrderFrom = 1.5;

// A feature that varies less than this over a window is left out of its
// fit (its column is zero): what varies less is rounding, not geometry.
constexpr double kFlatFeature = 1e-3;

// A thread's buffer for one column of weighted values.
std::vector<double>& window_scratch() {
    thread_local std::vector<double> scratch;
    return scratch;
}

// One pixel's window, ready to fit: the columns of its design matrix
// (each feature centred on the pixel's own and scaled to [-1, 1] over the
// window), the weights, and the Cholesky factor of XᵀWX plus the ridge.
// Columns are padded with zeros to a multiple of kLanes pixels, so that
// the sums over a window run kLanes at a time in a fixed order.
constexpr int kLanes = 16;  // four AVX registers of doubles: sums that do not wait on each other

struct Window {
    PixelRect rect;
    std::size_t padded = 0;  // pixels, padded to a multiple of kLanes
    std::array<std::vector<double>, kDesign> column;
    std::vector<double> weight;
    double weight_total = 0;
    bool constant = false;  // fitted by its weighted mean alone: no columns, no factor
    Eigen::LLT<NormalMatrix> llt;
};

// Σ x[i]·y[i] over `n` (a multiple of kLanes) values in four running
// sums of four lanes each, then those added in a fixed order.
double dot(const double* x, const double* y, std::size_t n) {
    double s0[4] = {}, s1[4] = {}, s2[4] = {}, s3[4] = {};
    for (std::size_t i = 0; i < n; i += kLanes) {
        for (std::size_t l = 0; l < 4; ++l) {
            s0[l] += x[i + l] * y[i + l];
            s1[l] += x[i + 4 + l] * y[i + 4 + l];
            s2[l] += x[i + 8 + l] * y[i + 8 + l];
            s3[l] += x[i + 12 + l] * y[i + 12 + l];
        }
    }
    double lane[4];
    for (std::size_t l = 0; l < 4; ++l) lane[l] = (s0[l] + s1[l]) + (s2[l] + s3[l]);
    return (lane[0] + lane[1]) + (lane[2] + lane[3]);
}

// `own_weights`: the pixel's non-local-means weights over its window.
void build_window(int px, int py, const float* own_weights, const Raster& features, const NlMeansParams& params,
                  Window& window) {
    const int radius = params.window_radius, side = window_side(params);
    window.rect = {std::max(px - radius, 0), std::max(py - radius, 0), std::min(px + radius + 1, features.width),
                   std::min(py + radius + 1, features.height)};
    const PixelRect& rect = window.rect;
    const std::size_t n = static_cast<std::size_t>(rect.width()) * static_cast<std::size_t>(rect.height());
    window.padded = (n + kLanes - 1) / kLanes * kLanes;
    // Every entry below n is written next; the padding is zero.
    for (std::vector<double>& column : window.column) {
        column.resize(window.padded);
        std::fill(column.begin() + static_cast<std::ptrdiff_t>(n), column.end(), 0.0);
    }
    window.weight.resize(window.padded);
    std::fill(window.weight.begin() + static_cast<std::ptrdiff_t>(n), window.weight.end(), 0.0);
    std::size_t i = 0;
    window.weight_total = 0;
    for (int qy = rect.y0; qy < rect.y1; ++qy)
        for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
            window.weight[i] = own_weights[(qy - py + radius) * side + (qx - px + radius)];
            window.weight_total += window.weight[i];
        }
    window.constant = window.weight_total < kFirstOrderFrom;
    if (window.constant) return;
    const float* fp = features.at(px, py);
    const double inverse_radius = 1.0 / std::max(radius, 1);
    i = 0;
    for (int qy = rect.y0; qy < rect.y1; ++qy) {
        for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
            window.column[0][i] = 1.0;
            window.column[1][i] = (qx - px) * inverse_radius;
            window.column[2][i] = (qy - py) * inverse_radius;
            const float* fq = features.at(qx, qy);
            for (int j = 0; j < kRegressionFeatures; ++j) window.column[3 + j][i] = static_cast<double>(fq[j] - fp[j]);
        }
    }
    for (int j = 3; j < kDesign; ++j) {
        // The largest |difference| among pixels of nonzero weight, lane by lane.
        double lane[kLanes] = {};
        const double* x = window.column[j].data();
        const double* w = window.weight.data();
        for (std::size_t k = 0; k < window.padded; k += kLanes)
            for (int l = 0; l < kLanes; ++l) {
                const std::size_t at = k + static_cast<std::size_t>(l);
                lane[l] = std::max(lane[l], w[at] > 0.0 ? std::abs(x[at]) : 0.0);
            }
        double spread = 0;
        for (const double v : lane) spread = std::max(spread, v);
        const double scale = spread > kFlatFeature ? 1.0 / spread : 0.0;
        for (std::size_t k = 0; k < n; ++k) window.column[j][k] *= scale;
    }

    NormalMatrix normal;
    std::vector<double>& weighted = window_scratch();
    weighted.resize(window.padded);
    for (int a = 0; a < kDesign; ++a) {
        for (std::size_t k = 0; k < window.padded; ++k) weighted[k] = window.weight[k] * window.column[a][k];
        for (int b = a; b < kDesign; ++b)
            normal(a, b) = normal(b, a) = dot(weighted.data(), window.column[b].data(), window.padded);
    }
    const double weight_total = normal(0, 0);
    for (int a = 1; a < kDesign; ++a) normal(a, a) += kRegressionRidge * weight_total;
    window.llt.compute(normal);
}

// Runs `visit(window)` for the windows of the tiles in `tiles` (in tile
// units): centred on every kCentreStride-th pixel along x and y, or, with
// `extra`, on the pixels it marks. Tiles run in four phases of a 2 × 2
// checkerboard, the tiles of one phase in parallel. Windows of two tiles
// of one phase never overlap (2R + 32 < 64), so a visit may add to the
// pixels of its window without a lock, and every pixel receives its sums
// in the same order whatever the thread count. Tiles not yet begun once
// `*cancel` is true are skipped.
template <typename Visit>
void for_each_window(const Raster& guide, const Raster& guide_variance, const Raster& features,
                     const NlMeansParams& params, PixelRect tiles, const std::vector<unsigned char>* extra,
                     const std::atomic<bool>* cancel, Visit visit) {
    const auto offsets = static_cast<std::size_t>(window_offsets(params));
    for (int phase = 0; phase < 4; ++phase) {
        std::vector<std::array<int, 2>> list;
        for (int ty = tiles.y0; ty < tiles.y1; ++ty)
            for (int tx = tiles.x0; tx < tiles.x1; ++tx)
                if ((tx & 1) == (phase & 1) && (ty & 1) == (phase >> 1)) list.push_back({tx, ty});
        tbb::parallel_for(std::size_t{0}, list.size(), [&](std::size_t t) {
            thread_local std::vector<float> weights, scratch;
            thread_local Window window;
            if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) return;
            const PixelRect tile = tile_rect(list[t][0], list[t][1], guide.width, guide.height);
            if (extra == nullptr) {
                nl_means_tile_weights(guide, guide_variance, tile, kCentreStride, params, weights, scratch);
                const float* own = weights.data();
                for (int py = tile.y0; py < tile.y1; py += kCentreStride)
                    for (int px = tile.x0; px < tile.x1; px += kCentreStride, own += offsets) {
                        build_window(px, py, own, features, params, window);
                        visit(window);
                    }
                return;
            }
            int marked = 0;
            for (int py = tile.y0; py < tile.y1; ++py)
                for (int px = tile.x0; px < tile.x1; ++px) marked += (*extra)[guide.pixel(px, py)];
            const bool whole_tile = marked * kOneCentreCost > tile.width() * tile.height();
            if (whole_tile) nl_means_tile_weights(guide, guide_variance, tile, 1, params, weights, scratch);
            for (int py = tile.y0; py < tile.y1; ++py)
                for (int px = tile.x0; px < tile.x1; ++px) {
                    if ((*extra)[guide.pixel(px, py)] == 0) continue;
                    // The pointer is taken after the weights are made: making them may reallocate.
                    std::size_t at = 0;
                    if (whole_tile)
                        at = static_cast<std::size_t>((py - tile.y0) * tile.width() + px - tile.x0) * offsets;
                    else
                        nl_means_tile_weights(guide, guide_variance, {px, py, px + 1, py + 1}, 1, params, weights,
                                              scratch);
                    build_window(px, py, weights.data() + at, features, params, window);
                    visit(window);
                }
        });
    }
}

// Each channel of `image` over the window, as padded columns.
void gather(const Raster& image, const Window& window, std::array<std::vector<double>, 3>& columns) {
    const std::size_t n =
        static_cast<std::size_t>(window.rect.width()) * static_cast<std::size_t>(window.rect.height());
    for (std::vector<double>& column : columns) {
        column.resize(window.padded);
        std::fill(column.begin() + static_cast<std::ptrdiff_t>(n), column.end(), 0.0);
    }
    std::size_t i = 0;
    for (int qy = window.rect.y0; qy < window.rect.y1; ++qy)
        for (int qx = window.rect.x0; qx < window.rect.x1; ++qx, ++i) {
            const float* v = image.at(qx, qy);
            for (int ch = 0; ch < 3; ++ch) columns[ch][i] = v[ch];
        }
}

// X·coefficients over the window: per channel, the fit's value at each pixel.
void predict(const Window& window, const Coefficients& coefficients, std::array<std::vector<double>, 3>& out) {
    for (int ch = 0; ch < 3; ++ch) {
        out[ch].assign(window.padded, 0.0);
        if (window.constant) {
            std::fill(out[ch].begin(), out[ch].end(), coefficients(0, ch));
            continue;
        }
        for (int a = 0; a < kDesign; ++a) {
            const double b = coefficients(a, ch);
            const double* x = window.column[a].data();
            double* o = out[ch].data();
            for (std::size_t k = 0; k < window.padded; ++k) o[k] += x[k] * b;
        }
    }
}

// Xᵀ·diag(scale)·columns: the right-hand side of a fit.
Coefficients weighted_sums(const Window& window, const std::vector<double>& scale,
                           const std::array<std::vector<double>, 3>& columns) {
    std::vector<double>& weighted = window_scratch();
    weighted.resize(window.padded);
    Coefficients sums = Coefficients::Zero();
    if (window.constant) {
        for (int ch = 0; ch < 3; ++ch) sums(0, ch) = dot(scale.data(), columns[ch].data(), window.padded);
        return sums;
    }
    for (int a = 0; a < kDesign; ++a) {
        for (std::size_t k = 0; k < window.padded; ++k) weighted[k] = scale[k] * window.column[a][k];
        for (int ch = 0; ch < 3; ++ch) sums(a, ch) = dot(weighted.data(), columns[ch].data(), window.padded);
    }
    return sums;
}

// (XᵀWX + ridge)⁻¹·sums; a constant window's fit is its sums over its total weight.
Coefficients solve(const Window& window, const Coefficients& sums) {
    if (!window.constant) return window.llt.solve(sums);
    Coefficients out = Coefficients::Zero();
    out.row(0) = sums.row(0) / window.weight_total;
    return out;
}

}  // namespace

RegressionResult collaborative_regression(const Raster& target, const Raster& guide, const Raster& guide_variance,
                                          const Raster& features, const NlMeansParams& params, int threads,
                                          const std::atomic<bool>* cancel) {
    const int width = target.width, height = target.height;
    RegressionResult result{Raster(width, height, 3), Raster(width, height, 1), {}};
    const auto fit = [&](const Window& window) {
        thread_local std::array<std::vector<double>, 3> values, prediction;
        gather(target, window, values);
        const Coefficients beta = solve(window, weighted_sums(window, window.weight, values));
        predict(window, beta, prediction);
        std::size_t i = 0;
        for (int qy = window.rect.y0; qy < window.rect.y1; ++qy)
            for (int qx = window.rect.x0; qx < window.rect.x1; ++qx, ++i) {
                const double w = window.weight[i];
                if (w <= 0.0) continue;
                float* out = result.value.at(qx, qy);
                for (int ch = 0; ch < 3; ++ch) out[ch] += static_cast<float>(w * prediction[ch][i]);
                *result.weight_sum.at(qx, qy) += static_cast<float>(w);
            }
    };
    const PixelRect tiles{0, 0, tile_count(width), tile_count(height)};
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        for_each_window(guide, guide_variance, features, params, tiles, nullptr, cancel, fit);
        result.own_window.assign(result.weight_sum.values.size(), 0);
        bool any = false;
        for (std::size_t p = 0; p < result.own_window.size(); ++p)
            if (result.weight_sum.values[p] < kOwnWindowBelow) {
                result.own_window[p] = 1;
                any = true;
            }
        if (any) for_each_window(guide, guide_variance, features, params, tiles, &result.own_window, cancel, fit);
    });
    if (cancel != nullptr && cancel->load()) return result;  // unfinished: sums of 0 stay
    // A pixel's weight in its own window is 1, so every sum is ≥ kOwnWindowBelow.
    for (std::size_t p = 0; p < result.weight_sum.values.size(); ++p)
        for (int ch = 0; ch < 3; ++ch) result.value.values[3 * p + ch] /= result.weight_sum.values[p];
    return result;
}

void collaborative_regression_adjoint(const Raster& guide, const Raster& guide_variance, const Raster& features,
                                      const NlMeansParams& params, const RegressionResult& forward, const Raster& g,
                                      PixelRect support, Raster& g_target) {
    if (support.empty()) return;
    const int radius = params.window_radius;
    // The windows that hold a pixel of the support are centred within R of it.
    const PixelRect centres{std::max(support.x0 - radius, 0), std::max(support.y0 - radius, 0),
                            std::min(support.x1 + radius, g.width), std::min(support.y1 + radius, g.height)};
    const PixelRect tiles{centres.x0 / kDenoiseTile, centres.y0 / kDenoiseTile, (centres.x1 - 1) / kDenoiseTile + 1,
                          (centres.y1 - 1) / kDenoiseTile + 1};
    const auto back_fit = [&](const Window& window) {
        const PixelRect& rect = window.rect;
        if (rect.x1 <= support.x0 || rect.x0 >= support.x1 || rect.y1 <= support.y0 || rect.y0 >= support.y1) return;
        // ∂value[q]/∂fit[q] = w_q / S_q: the collaborative mean's share of this window.
        std::vector<double> share(window.padded, 0.0);
        std::array<std::vector<double>, 3> g_values;
        gather(g, window, g_values);
        std::size_t i = 0;
        bool any = false;
        for (int qy = rect.y0; qy < rect.y1; ++qy)
            for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
                share[i] = window.weight[i] / *forward.weight_sum.at(qx, qy);
                any = any || g_values[0][i] != 0.0 || g_values[1][i] != 0.0 || g_values[2][i] != 0.0;
            }
        if (!any) return;
        const Coefficients u = solve(window, weighted_sums(window, share, g_values));
        std::array<std::vector<double>, 3> back;
        predict(window, u, back);
        i = 0;
        for (int qy = rect.y0; qy < rect.y1; ++qy)
            for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
                const double w = window.weight[i];
                if (w <= 0.0) continue;
                float* out = g_target.at(qx, qy);
                for (int ch = 0; ch < 3; ++ch) out[ch] += static_cast<float>(w * back[ch][i]);
            }
    };
    tbb::task_arena arena(1);  // one pixel's weights: small, and in a fixed order
    arena.execute([&] {
        for_each_window(guide, guide_variance, features, params, tiles, nullptr, nullptr, back_fit);
        for_each_window(guide, guide_variance, features, params, tiles, &forward.own_window, nullptr, back_fit);
    });
}

}  // namespace sombra
