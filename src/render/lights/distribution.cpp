#include "render/lights/distribution.h"

#include <algorithm>
#include <cmath>

namespace sombra {

namespace {

constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;  // the largest float below 1

float clamp_unit(float u) {
    if (!(u > 0.0f)) return 0.0f;  // negative or NaN
    return std::min(u, kOneMinusEpsilon);
}

// The bin i with cdf[i] <= u < cdf[i + 1]: a bin of width 0 (weight 0) never
// satisfies this, so it is never chosen.
int find_bin(const Distribution1D& d, float u) {
    const auto it = std::upper_bound(d.cdf.begin(), d.cdf.end(), u);
    const auto i = static_cast<int>(it - d.cdf.begin()) - 1;
    return std::clamp(i, 0, size(d) - 1);
}

}  // namespace

Distribution1D make_distribution_1d(std::span<const float> weights) {
    Distribution1D d;
    const std::size_t n = weights.size();
    d.weight.resize(n);
    d.cdf.resize(n + 1);
    if (n == 0) return d;

    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const float w = weights[i] > 0.0f && std::isfinite(weights[i]) ? weights[i] : 0.0f;
        d.weight[i] = w;
        sum += w;
    }
    // Prefix sums in double, so that a small weight still gets a bin of
    // non-zero width; after the last positive weight they are exactly `sum`.
    d.cdf[0] = 0.0f;
    if (sum > 0.0 && std::isfinite(sum) && static_cast<float>(sum) <= 3.4e38f) {
        double prefix = 0;
        for (std::size_t i = 0; i < n; ++i) {
            prefix += d.weight[i];
            d.cdf[i + 1] = static_cast<float>(prefix / sum);
        }
        d.total = static_cast<float>(sum);
        d.integral = static_cast<float>(sum / static_cast<double>(n));
    } else {  // the uniform fallback
        for (std::size_t i = 0; i < n; ++i)
            d.cdf[i + 1] = static_cast<float>(static_cast<double>(i + 1) / static_cast<double>(n));
    }
    d.cdf[n] = 1.0f;
    return d;
}

float probability(const Distribution1D& d, int index) {
    if (index < 0 || index >= size(d)) return 0.0f;
    if (d.total == 0.0f) return 1.0f / static_cast<float>(size(d));
    return d.weight[index] / d.total;
}

float pdf(const Distribution1D& d, int index) {
    if (index < 0 || index >= size(d)) return 0.0f;
    if (d.integral == 0.0f) return 1.0f;
    return d.weight[index] / d.integral;
}

ContinuousSample sample_continuous(const Distribution1D& d, float u) {
    if (size(d) == 0) return {};
    u = clamp_unit(u);
    const int i = find_bin(d, u);
    const float width = d.cdf[i + 1] - d.cdf[i];
    const float du = width > 0.0f ? std::clamp((u - d.cdf[i]) / width, 0.0f, 1.0f) : 0.0f;
    const float n = static_cast<float>(size(d));
    // x stays inside bin i (and below 1) despite rounding.
    const float lo = static_cast<float>(i) / n;
    const float hi = std::nextafter(static_cast<float>(i + 1) / n, 0.0f);
    const float x = std::clamp((static_cast<float>(i) + du) / n, lo, std::min(hi, kOneMinusEpsilon));
    return {x, pdf(d, i), i};
}

DiscreteSample sample_discrete(const Distribution1D& d, float u) {
    if (size(d) == 0) return {};
    const int i = find_bin(d, clamp_unit(u));
    return {i, probability(d, i)};
}

Distribution2D make_distribution_2d(std::span<const float> weights, int width, int height) {
    Distribution2D d;
    if (width <= 0 || height <= 0 || weights.size() < static_cast<std::size_t>(width) * height) return d;
    d.width = width;
    d.height = height;
    d.conditional.reserve(static_cast<std::size_t>(height));
    std::vector<float> row_integrals(static_cast<std::size_t>(height));
    for (int j = 0; j < height; ++j) {
        d.conditional.push_back(make_distribution_1d(
            weights.subspan(static_cast<std::size_t>(j) * width, static_cast<std::size_t>(width))));
        row_integrals[j] = d.conditional.back().integral;
    }
    d.marginal = make_distribution_1d(row_integrals);
    return d;
}

Sample2D sample(const Distribution2D& d, float u1, float u2) {
    if (d.width == 0) return {};
    const ContinuousSample row = sample_continuous(d.marginal, u2);
    const ContinuousSample column = sample_continuous(d.conditional[row.index], u1);
    return {column.x, row.x, column.pdf * row.pdf, column.index, row.index};
}

float pdf(const Distribution2D& d, float u, float v) {
    if (d.width == 0) return 0.0f;
    u = std::min(u >= 0.0f ? u : 0.0f, 1.0f);  // NaN too becomes 0
    v = std::min(v >= 0.0f ? v : 0.0f, 1.0f);
    const int i = std::clamp(static_cast<int>(u * static_cast<float>(d.width)), 0, d.width - 1);
    const int j = std::clamp(static_cast<int>(v * static_cast<float>(d.height)), 0, d.height - 1);
    if (d.marginal.integral == 0.0f) return 1.0f;  // the uniform fallback
    return d.conditional[j].weight[i] / d.marginal.integral;
}

}  // namespace sombra
