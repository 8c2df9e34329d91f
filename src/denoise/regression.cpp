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

// A ridge of kRidge · Σw on every column but the constant one keeps the
// fit well posed where features are collinear, while the constant column,
// left free, makes every pixel's weights add up to 1.
constexpr double kRidge = 1e-3;
// A feature that varies less than this over a window is left out of its
// fit (its column is zero): what varies less is rounding, not geometry.
constexpr float kFlatFeature = 1e-3f;

// One pixel's window, ready to fit: the rows of its design matrix (each
// feature centred on the pixel's own and scaled to [-1, 1] over the
// window), the weights, and the Cholesky factor of XᵀWX plus the ridge.
struct Window {
    PixelRect rect;
    std::vector<std::array<double, kDesign>> rows;
    std::vector<float> weight;
    Eigen::LLT<NormalMatrix> llt;
};

void build_window(int px, int py, PixelRect tile, const std::vector<float>& tile_weights, const Raster& features,
                  const NlMeansParams& params, Window& window) {
    const int radius = params.window_radius, side = window_side(params);
    window.rect = {std::max(px - radius, 0), std::max(py - radius, 0), std::min(px + radius + 1, features.width),
                   std::min(py + radius + 1, features.height)};
    const PixelRect& rect = window.rect;
    const std::size_t n = static_cast<std::size_t>(rect.width()) * static_cast<std::size_t>(rect.height());
    const std::size_t tile_n = static_cast<std::size_t>(tile.width()) * static_cast<std::size_t>(tile.height());
    const std::size_t centre = static_cast<std::size_t>(py - tile.y0) * static_cast<std::size_t>(tile.width()) +
                               static_cast<std::size_t>(px - tile.x0);
    window.rows.resize(n);
    window.weight.resize(n);
    const float* fp = features.at(px, py);
    std::array<float, kRegressionFeatures> spread{};
    std::size_t i = 0;
    for (int qy = rect.y0; qy < rect.y1; ++qy) {
        for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
            const int offset = (qy - py + radius) * side + (qx - px + radius);
            const float w = tile_weights[static_cast<std::size_t>(offset) * tile_n + centre];
            window.weight[i] = w;
            if (w <= 0.0f) continue;
            const float* fq = features.at(qx, qy);
            for (int j = 0; j < kRegressionFeatures; ++j) spread[j] = std::max(spread[j], std::abs(fq[j] - fp[j]));
        }
    }
    std::array<double, kRegressionFeatures> inverse_spread{};
    for (int j = 0; j < kRegressionFeatures; ++j) inverse_spread[j] = spread[j] > kFlatFeature ? 1.0 / spread[j] : 0.0;
    const double inverse_radius = 1.0 / std::max(radius, 1);

    std::array<std::array<double, kDesign>, kDesign> m{};
    double weight_total = 0;
    i = 0;
    for (int qy = rect.y0; qy < rect.y1; ++qy) {
        for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
            std::array<double, kDesign>& x = window.rows[i];
            const float* fq = features.at(qx, qy);
            x[0] = 1.0;
            x[1] = (qx - px) * inverse_radius;
            x[2] = (qy - py) * inverse_radius;
            for (int j = 0; j < kRegressionFeatures; ++j)
                x[3 + j] = static_cast<double>(fq[j] - fp[j]) * inverse_spread[j];
            const double w = window.weight[i];
            weight_total += w;
            for (int a = 0; a < kDesign; ++a) {
                const double wx = w * x[a];
                for (int b = 0; b < kDesign; ++b) m[a][b] += wx * x[b];
            }
        }
    }
    NormalMatrix normal;
    for (int a = 0; a < kDesign; ++a)
        for (int b = 0; b < kDesign; ++b) normal(a, b) = m[a][b];
    for (int a = 1; a < kDesign; ++a) normal(a, a) += kRidge * weight_total;
    window.llt.compute(normal);
}

// Runs `visit(px, py, tile, tile_weights, window)` for every pixel of the
// tiles in `tiles_x0…tiles_x1 × tiles_y0…tiles_y1` whose tile phase is
// (phase_x, phase_y), tiles of one phase in parallel. Windows of two
// tiles of one phase never overlap (2R + 32 < 64), so a visit may add to
// the pixels of its window without a lock, and every pixel receives its
// sums in the same order whatever the thread count. Tiles not yet begun
// once `*cancel` is true are skipped.
template <typename Visit>
void for_each_window(const Raster& guide, const Raster& guide_variance, const Raster& features,
                     const NlMeansParams& params, PixelRect tiles, const std::atomic<bool>* cancel, Visit visit) {
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
            nl_means_tile_weights(guide, guide_variance, tile, params, weights, scratch);
            for (int py = tile.y0; py < tile.y1; ++py)
                for (int px = tile.x0; px < tile.x1; ++px) {
                    build_window(px, py, tile, weights, features, params, window);
                    visit(window);
                }
        });
    }
}

}  // namespace

RegressionResult collaborative_regression(const Raster& target, const Raster& guide, const Raster& guide_variance,
                                          const Raster& features, const NlMeansParams& params, int threads,
                                          const std::atomic<bool>* cancel) {
    const int width = target.width, height = target.height;
    RegressionResult result{Raster(width, height, 3), Raster(width, height, 1)};
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        for_each_window(guide, guide_variance, features, params, {0, 0, tile_count(width), tile_count(height)}, cancel,
                        [&](const Window& window) {
                            const PixelRect& rect = window.rect;
                            Coefficients rhs = Coefficients::Zero();
                            std::size_t i = 0;
                            for (int qy = rect.y0; qy < rect.y1; ++qy)
                                for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
                                    const float* y = target.at(qx, qy);
                                    const double w = window.weight[i];
                                    for (int a = 0; a < kDesign; ++a) {
                                        const double wx = w * window.rows[i][a];
                                        for (int c = 0; c < 3; ++c) rhs(a, c) += wx * y[c];
                                    }
                                }
                            const Coefficients beta = window.llt.solve(rhs);
                            i = 0;
                            for (int qy = rect.y0; qy < rect.y1; ++qy)
                                for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
                                    const double w = window.weight[i];
                                    if (w <= 0.0) continue;
                                    float* out = result.value.at(qx, qy);
                                    for (int c = 0; c < 3; ++c) {
                                        double prediction = 0;
                                        for (int a = 0; a < kDesign; ++a) prediction += window.rows[i][a] * beta(a, c);
                                        out[c] += static_cast<float>(w * prediction);
                                    }
                                    *result.weight_sum.at(qx, qy) += static_cast<float>(w);
                                }
                        });
    });
    if (cancel != nullptr && cancel->load()) return result;  // unfinished: sums of 0 stay
    // Every pixel has weight 1 in its own window, so the sums are ≥ 1.
    for (std::size_t p = 0; p < result.weight_sum.values.size(); ++p)
        for (int c = 0; c < 3; ++c) result.value.values[3 * p + c] /= result.weight_sum.values[p];
    return result;
}

void collaborative_regression_adjoint(const Raster& guide, const Raster& guide_variance, const Raster& features,
                                      const NlMeansParams& params, const Raster& weight_sum, const Raster& g,
                                      PixelRect support, Raster& g_target) {
    if (support.empty()) return;
    const int radius = params.window_radius;
    // The windows that hold a pixel of the support are centred within R of it.
    const PixelRect centres{std::max(support.x0 - radius, 0), std::max(support.y0 - radius, 0),
                            std::min(support.x1 + radius, g.width), std::min(support.y1 + radius, g.height)};
    const PixelRect tiles{centres.x0 / kDenoiseTile, centres.y0 / kDenoiseTile, (centres.x1 - 1) / kDenoiseTile + 1,
                          (centres.y1 - 1) / kDenoiseTile + 1};
    tbb::task_arena arena(1);  // one pixel's weights: small, and in a fixed order
    arena.execute([&] {
        for_each_window(guide, guide_variance, features, params, tiles, nullptr, [&](const Window& window) {
            const PixelRect& rect = window.rect;
            if (rect.x1 <= support.x0 || rect.x0 >= support.x1 || rect.y1 <= support.y0 || rect.y0 >= support.y1)
                return;
            Coefficients v = Coefficients::Zero();
            std::size_t i = 0;
            for (int qy = rect.y0; qy < rect.y1; ++qy)
                for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
                    const float* gq = g.at(qx, qy);
                    if (gq[0] == 0.0f && gq[1] == 0.0f && gq[2] == 0.0f) continue;
                    const double scale = window.weight[i] / *weight_sum.at(qx, qy);
                    for (int a = 0; a < kDesign; ++a)
                        for (int c = 0; c < 3; ++c) v(a, c) += scale * window.rows[i][a] * gq[c];
                }
            if (v.isZero(0.0)) return;
            const Coefficients u = window.llt.solve(v);
            i = 0;
            for (int qy = rect.y0; qy < rect.y1; ++qy)
                for (int qx = rect.x0; qx < rect.x1; ++qx, ++i) {
                    const double w = window.weight[i];
                    if (w <= 0.0) continue;
                    float* out = g_target.at(qx, qy);
                    for (int c = 0; c < 3; ++c) {
                        double sum = 0;
                        for (int a = 0; a < kDesign; ++a) sum += window.rows[i][a] * u(a, c);
                        out[c] += static_cast<float>(w * sum);
                    }
                }
        });
    });
}

}  // namespace sombra
