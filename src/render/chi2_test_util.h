// A χ² goodness-of-fit test of a direction sampler against the pdf it claims,
// for tests of BSDF and light sampling (as Nori's chi2test and Mitsuba's
// ChiSquareTest): draw N directions, histogram them over bins of equal solid
// angle in (cos θ, φ) of a frame, integrate the pdf over each bin numerically
// for the expected counts, pool the bins expected to hold fewer than 5
// samples, and compare by Pearson's χ² with a Šidák-corrected significance.
//
// Header-only and for tests: it allocates, and is not on any hot path.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/vec3.h"

namespace sombra::chi2 {

// The regularised upper incomplete gamma function Q(a, x) = Γ(a, x)/Γ(a), for
// a > 0, x ≥ 0: a series for x < a + 1, Lentz's continued fraction otherwise
// (Numerical Recipes §6.2). Q(k/2, χ²/2) is the p-value of χ² with k degrees of freedom.
inline double gamma_q(double a, double x) {
    if (x <= 0.0) return 1.0;
    const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1.0) {  // P(a, x) = e^−x x^a / Γ(a) · Σ x^n / (a (a+1) … (a+n))
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 10000 && std::fabs(term) > std::fabs(sum) * 1e-16; ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return std::clamp(1.0 - sum * std::exp(log_prefactor), 0.0, 1.0);
    }
    constexpr double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-16) break;
    }
    return std::clamp(std::exp(log_prefactor) * h, 0.0, 1.0);
}

// ∫_a^b f by adaptive Simpson: an interval is split until the halves agree
// with the whole within 15·eps (Richardson), at least min_depth and at most
// max_depth times. eps halves with each split, down to eps/1024: without that
// floor a discontinuity, or a slightly noisy f (an inner integral), would be
// split to max_depth everywhere. f must be finite.
// An interval also stops splitting when its halves agree within rel of their
// sum: the pdf is a float, whose rounding near a sharp peak no absolute
// tolerance can beat.
template <class F>
double adaptive_simpson(const F& f, double a, double b, double eps, int min_depth, int max_depth, double rel = 1e-4) {
    struct Rec {
        const F& f;
        int min_depth, max_depth;
        double eps_floor, rel;
        double run(double a, double b, double fa, double fm, double fb, double whole, double eps, int depth) const {
            const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
            const double flm = f(lm), frm = f(rm);
            const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
            const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
            const double diff = left + right - whole;
            const bool converged = std::fabs(diff) <= 15.0 * eps || std::fabs(diff) <= rel * std::fabs(left + right);
            if (depth >= max_depth || (depth >= min_depth && converged)) return left + right + diff / 15.0;
            const double half = std::max(0.5 * eps, eps_floor);
            return run(a, m, fa, flm, fm, left, half, depth + 1) + run(m, b, fm, frm, fb, right, half, depth + 1);
        }
    };
    const double fa = f(a), fm = f(0.5 * (a + b)), fb = f(b);
    const double whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    return Rec{f, min_depth, max_depth, eps / 1024.0, rel}.run(a, b, fa, fm, fb, whole, eps, 0);
}

// Pearson's χ² of observed counts against expected ones, for any binning.
struct Pearson {
    double chi2 = 0;
    int dof = 0;         // bins used (after pooling) − 1
    double p_value = 1;  // Q(dof/2, χ²/2); 1 when fewer than 2 bins remain; 0 for a bad bin
    long bad_bin = -1;   // a bin that expects nothing yet holds more than `slack` samples, or −1
};

// Bins expecting fewer than `min_expected` are pooled, smallest expectation
// first, until the pooled group expects at least that; bins expecting 0 may
// hold up to `slack` samples (integration error), more makes the test fail
// with p = 0 and bad_bin set.
inline Pearson pearson(const std::vector<double>& observed, const std::vector<double>& expected,
                       double min_expected = 5, double slack = 0) {
    Pearson res;
    std::vector<std::size_t> order(observed.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
    double pooled_obs = 0, pooled_exp = 0;
    int bins = 0;
    for (const std::size_t k : order) {
        if (expected[k] <= 0.0) {
            if (observed[k] > slack) {
                res.bad_bin = static_cast<long>(k);
                res.p_value = 0;
                return res;
            }
            pooled_obs += observed[k];
        } else if (expected[k] < min_expected || (pooled_exp > 0 && pooled_exp < min_expected)) {
            pooled_obs += observed[k];
            pooled_exp += expected[k];
        } else {
            res.chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
            ++bins;
        }
    }
    if (pooled_exp > 0) {
        res.chi2 += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        ++bins;
    }
    res.dof = bins - 1;
    res.p_value = res.dof < 1 ? 1.0 : gamma_q(0.5 * res.dof, 0.5 * res.chi2);
    return res;
}

struct Options {
    int cos_bins = 10;        // bins in cos θ of the frame: over [−1, 1], or [0, 1] when hemisphere
    int phi_bins = 20;        // bins in φ over [0, 2π)
    bool hemisphere = false;  // bin only the frame's upper hemisphere (a sample below it fails the test)
    std::uint32_t samples = 200000;
    double min_expected = 5;  // bins expected to hold fewer samples are pooled
    double alpha = 0.01;      // significance level of the whole suite…
    int test_count = 1;       // …split over this many χ² tests (Šidák): each uses 1 − (1 − α)^(1/test_count)
    double integration_eps = 1e-7;      // absolute tolerance of each bin's integral of the pdf (probability)…
    double integration_rel = 1e-4;      // …or this fraction of the bin's probability (first estimate), if larger
    int min_depth = 3, max_depth = 18;  // adaptive Simpson subdivisions per dimension
};

struct Result {
    double chi2 = 0;              // Pearson's statistic over the (pooled) bins
    int dof = 0;                  // degrees of freedom: bins used − 1
    double p_value = 1;           // Q(dof/2, χ²/2)
    double significance = 0;      // the per-test (Šidák) level p_value is compared with
    bool passed = false;          // p_value > significance, and no sample where the pdf is 0
    double pdf_integral = 0;      // ∫ pdf dω over the binned domain (1 for a sampler that never fails)
    double success_fraction = 0;  // samples that produced a direction / samples drawn
    long pdf_evaluations = 0;     // calls of pdf by the integration (its cost)
    std::string message;          // why it failed, or a summary
};

// The unit direction at (cos θ = z, φ) of frame.
inline Vec3 direction_at(const Frame& frame, double z, double phi) {
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return frame.to_world(
        Vec3{static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)), static_cast<float>(z)});
}

// sample(i) → std::optional<Vec3>: the i-th sampled unit direction (world
// space), or nothing when the sampler failed; it draws its own random numbers,
// e.g. from hash_to_unit(i, key). pdf(Vec3 world direction) → solid-angle
// density in 1/sr, finite. Bins are of equal solid angle in frame's (cos θ, φ).
template <class SampleFn, class PdfFn>
Result run(const Frame& frame, const SampleFn& sample, const PdfFn& pdf, const Options& o) {
    constexpr double two_pi = 2.0 * std::numbers::pi;
    const double z0 = o.hemisphere ? 0.0 : -1.0;
    const double dz = (1.0 - z0) / o.cos_bins, dphi = two_pi / o.phi_bins;
    // Cell (iz, ip) of the cos_bins × phi_bins grid, row by row.
    const auto cell = [&](int iz, int ip) {
        return static_cast<std::size_t>(iz) * static_cast<std::size_t>(o.phi_bins) + static_cast<std::size_t>(ip);
    };
    const std::size_t cells = cell(o.cos_bins, 0);
    std::vector<double> observed(cells, 0.0), expected(cells, 0.0);
    Result res;

    std::uint32_t successes = 0, outside = 0;
    for (std::uint32_t i = 0; i < o.samples; ++i) {
        const std::optional<Vec3> d = sample(i);
        if (!d) continue;
        ++successes;
        const Vec3 l = frame.to_local(*d);
        const double z = std::clamp(static_cast<double>(l.z), -1.0, 1.0);
        if (z < z0) {
            ++outside;
            continue;
        }
        double phi = std::atan2(static_cast<double>(l.y), static_cast<double>(l.x));
        if (phi < 0) phi += two_pi;
        const int iz = std::clamp(static_cast<int>((z - z0) / dz), 0, o.cos_bins - 1);
        const int ip = std::clamp(static_cast<int>(phi / dphi), 0, o.phi_bins - 1);
        observed[cell(iz, ip)] += 1.0;
    }
    res.success_fraction = static_cast<double>(successes) / o.samples;

    const double n = o.samples;
    for (int iz = 0; iz < o.cos_bins; ++iz) {
        for (int ip = 0; ip < o.phi_bins; ++ip) {
            const double za = z0 + iz * dz, zb = iz + 1 == o.cos_bins ? 1.0 : za + dz;
            const double pa = ip * dphi, pb = (ip + 1) * dphi;
            // dω = dz dφ: the inner integral over φ at each z, then over z.
            const auto f = [&](double z, double phi) {
                ++res.pdf_evaluations;
                return static_cast<double>(pdf(direction_at(frame, z, phi)));
            };
            // A first estimate on a 9×9 grid sets the relative tolerance.
            double guess = 0;
            for (int a = 0; a < 9; ++a)
                for (int b = 0; b < 9; ++b) guess += f(za + (a + 0.5) / 9 * (zb - za), pa + (b + 0.5) / 9 * (pb - pa));
            guess *= (zb - za) * (pb - pa) / 81;
            const double eps = std::max(o.integration_eps, o.integration_rel * guess);
            const auto ring = [&](double z) {
                return adaptive_simpson([&](double phi) { return f(z, phi); }, pa, pb, eps / dz, o.min_depth,
                                        o.max_depth, 0.25 * o.integration_rel);
            };
            const double mass = adaptive_simpson(ring, za, zb, eps, o.min_depth, o.max_depth, o.integration_rel);
            expected[cell(iz, ip)] = mass * n;
            res.pdf_integral += mass;
        }
    }

    res.significance = 1.0 - std::pow(1.0 - o.alpha, 1.0 / std::max(1, o.test_count));
    if (outside > 0) {
        res.message = std::to_string(outside) + " samples below the frame's hemisphere";
        return res;
    }
    // When the sampler can fail, its failures are one more bin, expecting N·(1 − ∫pdf).
    if (successes < o.samples) {
        observed.push_back(n - successes);
        expected.push_back(n * std::max(0.0, 1.0 - res.pdf_integral));
    }
    // Nori's slack for integration error: a handful of samples where the pdf integrates to 0.
    const Pearson pearson_result = pearson(observed, expected, o.min_expected, n * 1e-5);
    if (pearson_result.bad_bin >= 0) {
        const auto k = static_cast<std::size_t>(pearson_result.bad_bin);
        res.message = std::to_string(static_cast<long>(observed[k])) +
                      (k == cells ? " failed samples though the pdf integrates to 1"
                                  : " samples in bin (cos " + std::to_string(k / o.phi_bins) + ", phi " +
                                        std::to_string(k % o.phi_bins) + ") whose pdf integrates to 0");
        return res;
    }
    res.chi2 = pearson_result.chi2;
    res.dof = pearson_result.dof;
    if (res.dof < 1) {
        res.p_value = 1;
        res.passed = true;
        res.message = "fewer than 2 bins: no test";
        return res;
    }
    res.p_value = pearson_result.p_value;
    res.passed = res.p_value > res.significance;
    res.message = "chi2 = " + std::to_string(res.chi2) + ", dof = " + std::to_string(res.dof) +
                  ", p = " + std::to_string(res.p_value) + " (level " + std::to_string(res.significance) +
                  "), integral = " + std::to_string(res.pdf_integral) +
                  ", successes = " + std::to_string(res.success_fraction) +
                  ", pdf calls = " + std::to_string(res.pdf_evaluations);
    return res;
}

}  // namespace sombra::chi2
