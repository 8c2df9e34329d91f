// Piecewise-constant probability distributions for importance sampling: one
// dimension (choosing a light in proportion to its power, a column of an
// image) and two (a texel of an environment map in proportion to its weight).
// Built once, then sampled with no allocation.
#pragma once

#include <span>
#include <vector>

namespace sombra {

// A distribution over n bins of equal width 1/n on [0, 1), bin i having
// probability weight[i] / Σ weight. Built by make_distribution_1d.
//
// All weights zero (or the sum not a positive finite number): the
// distribution falls back to uniform, every bin having probability 1/n, and
// `integral` is 0 so that the caller can tell (a black environment, lights
// with no power). Empty (n = 0): nothing can be sampled; the sample functions
// return index −1 and a pdf of 0.
struct Distribution1D {
    std::vector<float> weight;  // the weights as given, negatives and NaN made 0
    std::vector<float> cdf;     // n + 1 entries: cdf[0] = 0, cdf[n] = 1, non-decreasing
    float total = 0;            // Σ weight, 0 when all are zero
    float integral = 0;         // Σ weight / n: the integral over [0, 1) of the step function
};

Distribution1D make_distribution_1d(std::span<const float> weights);

inline int size(const Distribution1D& d) { return static_cast<int>(d.weight.size()); }

// A point x in [0, 1) distributed with density pdf(x) = weight[i] / integral
// on bin i = floor(x·n) (1 under the uniform fallback). A bin of weight 0 is
// never chosen (unless all are). The cdf is float: a weight below about 1e-7
// of the total may get a bin of width 0 and never be chosen although its pdf
// is > 0 (u, a float, could not resolve it anyway); callers that need every
// positive weight reachable keep weights above such a floor.
struct ContinuousSample {
    float x = 0;
    float pdf = 0;   // density w.r.t. x on [0, 1)
    int index = -1;  // the bin x lies in
};
// u uniform in [0, 1) (values ≥ 1 are taken as just below 1).
ContinuousSample sample_continuous(const Distribution1D& d, float u);

// A bin chosen with probability weight[i] / total (1/n under the fallback).
struct DiscreteSample {
    int index = -1;
    float probability = 0;
};
DiscreteSample sample_discrete(const Distribution1D& d, float u);

// The probability sample_discrete chooses bin `index` (0 outside [0, n)).
float probability(const Distribution1D& d, int index);
// The density sample_continuous has on bin `index` (0 outside [0, n)).
float pdf(const Distribution1D& d, int index);

// A distribution over the unit square [0, 1)², piecewise constant on a
// width × height grid of cells; cell (i, j), column i from u = 0, row j from
// v = 0, has probability weight[j·width + i] / Σ weight. Sampled by picking
// the row from the marginal (the rows' sums), then the column from that row's
// conditional. Zero weights everywhere: uniform over the square, with
// `marginal.integral` 0.
struct Distribution2D {
    int width = 0, height = 0;
    std::vector<Distribution1D> conditional;  // one per row, over its columns
    Distribution1D marginal;                  // over the rows, weighted by their integrals
};

// `weights` holds width × height values, row by row (row 0 first).
Distribution2D make_distribution_2d(std::span<const float> weights, int width, int height);

struct Sample2D {
    float u = 0, v = 0;  // in [0, 1)²
    float pdf = 0;       // density w.r.t. area on [0, 1)²; 0 only for an empty distribution
    int column = -1, row = -1;
};
// u1 chooses the column (u), u2 the row (v); both uniform in [0, 1).
Sample2D sample(const Distribution2D& d, float u1, float u2);

// The density of sample() at (u, v) w.r.t. area on [0, 1)² (coordinates
// outside are clamped to the nearest cell).
float pdf(const Distribution2D& d, float u, float v);

}  // namespace sombra
