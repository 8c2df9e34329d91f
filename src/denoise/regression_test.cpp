// The collaborative regression against a brute-force solve, and its
// adjoint against the forward run.
#include "denoise/regression.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <random>
#include <vector>

#include "denoise/denoise_test_util.h"

namespace sombra {
namespace {

using test::random_raster;

struct Inputs {
    Raster target, guide, variance, features;
};

Inputs random_inputs(int w, int h, unsigned seed) {
    return {random_raster(w, h, 3, 0.0f, 1.0f, seed), random_raster(w, h, 3, 0.0f, 1.0f, seed + 1),
            random_raster(w, h, 3, 0.05f, 0.3f, seed + 2),
            random_raster(w, h, kRegressionFeatures, -1.0f, 1.0f, seed + 3)};
}

// A guide value far above its neighbours at each of `pixels`: a firefly
// that no window of the grid trusts, so it gets a window of its own.
void add_fireflies(Inputs& in, std::initializer_list<std::array<int, 2>> pixels) {
    for (const auto& [x, y] : pixels)
        for (int c = 0; c < 3; ++c) in.guide.at(x, y)[c] = 40.0f;
}

// The regression as the paper states it, one window at a time: the
// weighted ridge least-squares fit solved by a QR of the stacked system
// [√W·X; √λ·I'] (I' without the constant column), in doubles; windows
// centred on the pixels of even x and y, then on each pixel those gave
// a total weight below 1. `own_windows` counts the latter.
Raster brute_force(const Inputs& in, const NlMeansParams& params, int& own_windows) {
    const int w = in.target.width, h = in.target.height, R = params.window_radius, side = window_side(params);
    std::vector<float> weights, scratch;
    nl_means_tile_weights(in.guide, in.variance, PixelRect{0, 0, w, h}, 1, params, weights, scratch);
    const std::size_t n_all = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    std::vector<double> sum(3 * n_all, 0.0), total(n_all, 0.0);
    constexpr int d = 3 + kRegressionFeatures;
    const auto fit = [&](int px, int py) {
        {
            std::vector<std::array<int, 2>> qs;
            std::vector<double> ws;
            for (int qy = std::max(py - R, 0); qy < std::min(py + R + 1, h); ++qy)
                for (int qx = std::max(px - R, 0); qx < std::min(px + R + 1, w); ++qx) {
                    qs.push_back({qx, qy});
                    ws.push_back(weights[static_cast<std::size_t>(py * w + px) * static_cast<std::size_t>(side * side) +
                                         static_cast<std::size_t>((qy - py + R) * side + qx - px + R)]);
                }
            const auto n = static_cast<int>(qs.size());
            double spread[kRegressionFeatures] = {};
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < kRegressionFeatures; ++j)
                    if (ws[i] > 0)
                        spread[j] =
                            std::max(spread[j], std::abs(static_cast<double>(in.features.at(qs[i][0], qs[i][1])[j]) -
                                                         in.features.at(px, py)[j]));
            Eigen::MatrixXd x(n, d);
            Eigen::MatrixXd y(n, 3);
            double wsum = 0;
            for (int i = 0; i < n; ++i) {
                x(i, 0) = 1;
                x(i, 1) = (qs[i][0] - px) / double(R);
                x(i, 2) = (qs[i][1] - py) / double(R);
                for (int j = 0; j < kRegressionFeatures; ++j)
                    x(i, 3 + j) =
                        spread[j] > 1e-3
                            ? (static_cast<double>(in.features.at(qs[i][0], qs[i][1])[j]) - in.features.at(px, py)[j]) /
                                  spread[j]
                            : 0.0;
                for (int c = 0; c < 3; ++c) y(i, c) = in.target.at(qs[i][0], qs[i][1])[c];
                wsum += ws[i];
            }
            Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + d - 1, d);
            Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n + d - 1, 3);
            for (int i = 0; i < n; ++i) {
                a.row(i) = std::sqrt(ws[i]) * x.row(i);
                b.row(i) = std::sqrt(ws[i]) * y.row(i);
            }
            for (int j = 1; j < d; ++j) a(n + j - 1, j) = std::sqrt(kRegressionRidge * wsum);
            Eigen::MatrixXd prediction = x * a.colPivHouseholderQr().solve(b);
            if (wsum < 1.5) {
                // Neighbours that weigh less than half the centre: the window's weighted mean.
                Eigen::RowVectorXd mean = Eigen::RowVectorXd::Zero(3);
                for (int i = 0; i < n; ++i) mean += ws[i] * y.row(i) / wsum;
                prediction = mean.replicate(n, 1);
            }
            for (int i = 0; i < n; ++i) {
                const std::size_t q = static_cast<std::size_t>(qs[i][1]) * static_cast<std::size_t>(w) +
                                      static_cast<std::size_t>(qs[i][0]);
                for (int c = 0; c < 3; ++c) sum[3 * q + c] += ws[i] * prediction(i, c);
                total[q] += ws[i];
            }
        }
    };
    for (int py = 0; py < h; py += 2)
        for (int px = 0; px < w; px += 2) fit(px, py);
    const std::vector<double> grid_total = total;
    own_windows = 0;
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px)
            if (grid_total[static_cast<std::size_t>(py) * static_cast<std::size_t>(w) + static_cast<std::size_t>(px)] <
                1.0) {
                fit(px, py);
                ++own_windows;
            }
    Raster out(w, h, 3);
    for (std::size_t q = 0; q < n_all; ++q)
        for (int c = 0; c < 3; ++c) out.values[3 * q + c] = static_cast<float>(sum[3 * q + c] / total[q]);
    return out;
}

TEST(CollaborativeRegression, MatchesABruteForceSolve) {
    const NlMeansParams params{3, 1, 1.0f};
    Inputs in = random_inputs(11, 9, 10);
    add_fireflies(in, {{3, 3}, {8, 5}});
    const RegressionResult fast = collaborative_regression(in.target, in.guide, in.variance, in.features, params, 2);
    int own_windows = 0;
    const Raster slow = brute_force(in, params, own_windows);
    for (std::size_t i = 0; i < fast.value.values.size(); ++i)
        EXPECT_NEAR(fast.value.values[i], slow.values[i], 1e-5) << i;
    EXPECT_GT(own_windows, 0);
    EXPECT_EQ(std::count(fast.own_window.begin(), fast.own_window.end(), 1), own_windows);
}

TEST(CollaborativeRegression, KeepsAConstant) {
    const NlMeansParams params{9, 3, 0.5f};
    Inputs in = random_inputs(45, 38, 20);
    in.target = Raster(45, 38, 3, 1.75f);
    for (const float v :
         collaborative_regression(in.target, in.guide, in.variance, in.features, params, 2).value.values)
        EXPECT_NEAR(v, 1.75f, 2e-6f);
}

TEST(CollaborativeRegression, ReproducesATargetTheFeaturesExplain) {
    // A noise-free target affine in one feature and in position: each
    // window's fit is exact (up to the small ridge), so the output is the target.
    const NlMeansParams params{9, 3, 1.0f};
    Inputs in = random_inputs(40, 33, 30);
    for (int y = 0; y < 33; ++y)
        for (int x = 0; x < 40; ++x)
            for (int c = 0; c < 3; ++c)
                in.target.at(x, y)[c] = 0.5f + 0.25f * in.features.at(x, y)[0] + 0.01f * static_cast<float>(x);
    in.guide = in.target;
    in.variance = Raster(40, 33, 3, 0.0f);
    const Raster out = collaborative_regression(in.target, in.guide, in.variance, in.features, params, 2).value;
    for (std::size_t i = 0; i < out.values.size(); ++i) EXPECT_NEAR(out.values[i], in.target.values[i], 1e-5f) << i;
}

TEST(CollaborativeRegression, SameBytesOnAnyThreadCount) {
    const NlMeansParams params{9, 3, 0.5f};
    const Inputs in = random_inputs(101, 70, 40);
    const RegressionResult one = collaborative_regression(in.target, in.guide, in.variance, in.features, params, 1);
    const RegressionResult three = collaborative_regression(in.target, in.guide, in.variance, in.features, params, 3);
    EXPECT_EQ(one.value.values, three.value.values);
    EXPECT_EQ(one.weight_sum.values, three.weight_sum.values);
}

TEST(CollaborativeRegression, AdjointIsTheTransposeOfTheForwardMap) {
    // For a fixed guide the output is L·target; the adjoint must give Lᵀ·g,
    // so that ⟨g, L·y⟩ = ⟨Lᵀ·g, y⟩ for any y, and for g one pixel's indicator
    // its row of L (weights adding up to 1).
    const NlMeansParams params{9, 3, 0.5f};
    Inputs in = random_inputs(70, 50, 50);
    add_fireflies(in, {{39, 31}, {43, 35}, {41, 33}});
    const RegressionResult forward = collaborative_regression(in.target, in.guide, in.variance, in.features, params, 2);
    Raster g(70, 50, 3);
    const int px = 41, py = 33;
    for (int c = 0; c < 3; ++c) g.at(px, py)[c] = 1.0f;
    Raster row(70, 50, 3);
    // The row must cover the pixels' own windows as well as the grid's.
    EXPECT_GT(std::count(forward.own_window.begin(), forward.own_window.end(), 1), 0);
    collaborative_regression_adjoint(in.guide, in.variance, in.features, params, forward, g,
                                     PixelRect{px, py, px + 1, py + 1}, row);
    for (int c = 0; c < 3; ++c) {
        double total = 0, value = 0, magnitude = 0;
        for (std::size_t q = 0; q < 70 * 50; ++q) {
            total += row.values[3 * q + c];
            value += static_cast<double>(row.values[3 * q + c]) * in.target.values[3 * q + c];
            magnitude += std::abs(static_cast<double>(row.values[3 * q + c]) * in.target.values[3 * q + c]);
        }
        EXPECT_NEAR(total, 1.0, 1e-4);
        EXPECT_NEAR(value, forward.value.at(px, py)[c], 1e-4 * magnitude + 1e-6);
    }
    // Outside the windows around the pixel (within 2R), nothing.
    for (int y = 0; y < 50; ++y)
        for (int x = 0; x < 70; ++x)
            if (std::abs(x - px) > 18 || std::abs(y - py) > 18) {
                EXPECT_EQ(row.at(x, y)[0], 0.0f);
            }
}

}  // namespace
}  // namespace sombra
