// Tracking through a grid medium: z-tests (fixed seeds, the sample variance)
// that ratio tracking's transmittance and delta tracking's free flights are
// unbiased against closed forms for a density ramp, per channel of a
// coloured medium, and stay so when the majorants are doubled; and that the
// majorant grid bounds every interpolated density.
#include "render/media/grid_medium.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>

namespace sombra {
namespace {

float channel(Vec3 v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }

// A dense grid of dims voxels, value f(i, j, k), world = dense coordinates.
Medium grid_medium(std::array<int, 3> dims, const std::function<float(int, int, int)>& f, Vec3 sigma_a, Vec3 sigma_s,
                   float majorant_factor = 1.0f) {
    auto grid = std::make_shared<DensityGrid>();
    grid->dims = dims;
    for (int k = 0; k < dims[2]; ++k)
        for (int j = 0; j < dims[1]; ++j)
            for (int i = 0; i < dims[0]; ++i) grid->values.push_back(f(i, j, k));
    build_majorants(*grid);
    for (float& m : grid->majorants) m *= majorant_factor;
    Medium m;
    m.sigma_a = sigma_a;
    m.sigma_s = sigma_s;
    m.density = grid;
    return m;
}

// A ramp along x on the row y = z = 1: voxel i holds 0.1·i inside, 0 on the padding.
constexpr int kLength = 40;
float ramp(int i, int j, int k) {
    return j == 1 && k == 1 && i > 0 && i < kLength - 1 ? 0.1f * static_cast<float>(i) : 0.0f;
}
// ∫ from x = a to b of 0.1·x dx.
double ramp_integral(double a, double b) { return 0.05 * (b * b - a * a); }

const Vec3 kSigmaA{0.02f, 0.05f, 0.0f}, kSigmaS{0.03f, 0.05f, 0.1f};

// Per-channel z-test of the mean of f(rng) over n draws against `expected`.
template <class F>
void expect_mean(F f, int n, std::uint64_t seed, Vec3 expected, const char* what) {
    TrackingRng rng{seed};
    std::array<double, 3> sum{}, sum_sq{};
    for (int i = 0; i < n; ++i) {
        const Vec3 v = f(rng);
        for (int c = 0; c < 3; ++c) {
            sum[c] += channel(v, c);
            sum_sq[c] += static_cast<double>(channel(v, c)) * channel(v, c);
        }
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / n, variance = std::max(0.0, (sum_sq[c] - n * mean * mean) / (n - 1));
        const double error = std::sqrt(variance / n);
        if (error < 1e-9) {
            EXPECT_NEAR(mean, channel(expected, c), 1e-5) << what << " channel " << c;
        } else {
            EXPECT_LT(std::fabs(mean - channel(expected, c)) / error, 4.5)
                << what << " channel " << c << ": mean " << mean << " ± " << error << ", expected "
                << channel(expected, c);
        }
    }
}

// exp(−σ_t·τ) per channel, τ the density's integral.
Vec3 expected_transmittance(double tau) {
    const Vec3 sigma_t = kSigmaA + kSigmaS;
    return {static_cast<float>(std::exp(-sigma_t.x * tau)), static_cast<float>(std::exp(-sigma_t.y * tau)),
            static_cast<float>(std::exp(-sigma_t.z * tau))};
}

TEST(GridMedium, TheMajorantsBoundEveryInterpolatedDensity) {
    const Medium m = grid_medium(
        {20, 13, 9}, [](int i, int j, int k) { return static_cast<float>((i * 7 + j * 3 + k) % 5); }, Vec3{1.0f},
        Vec3{0.0f});
    const DensityGrid& g = *m.density;
    TrackingRng rng{1};
    for (int n = 0; n < 20000; ++n) {
        const Vec3 q{rng.next() * 19.0f, rng.next() * 12.0f, rng.next() * 8.0f};
        const int a = std::min(static_cast<int>(q.x) / kMajorantBlock, g.cells[0] - 1);
        const int b = std::min(static_cast<int>(q.y) / kMajorantBlock, g.cells[1] - 1);
        const int c = std::min(static_cast<int>(q.z) / kMajorantBlock, g.cells[2] - 1);
        const std::size_t cell =
            static_cast<std::size_t>(a) +
            static_cast<std::size_t>(g.cells[0]) *
                (static_cast<std::size_t>(b) + static_cast<std::size_t>(g.cells[1]) * static_cast<std::size_t>(c));
        const float majorant = g.majorants[cell];
        ASSERT_LE(density_at(g, q), majorant) << q.x << " " << q.y << " " << q.z;
    }
    EXPECT_EQ(g.max_value, 4.0f);
}

TEST(GridMedium, InterpolationIsTrilinearAndZeroOutside) {
    const Medium m = grid_medium(
        {4, 4, 4}, [](int i, int j, int k) { return static_cast<float>(i + 2 * j + 4 * k); }, Vec3{1.0f}, Vec3{0.0f});
    EXPECT_FLOAT_EQ(density_at(*m.density, {1.25f, 1.5f, 2.75f}), 1.25f + 3.0f + 11.0f);
    EXPECT_EQ(density_at(*m.density, {-0.5f, 1.0f, 1.0f}), 0.0f);
    EXPECT_EQ(density_at(*m.density, {1.0f, 3.5f, 1.0f}), 0.0f);
}

TEST(GridMedium, RatioTrackingIsUnbiasedForARamp) {
    for (const float factor : {1.0f, 2.0f}) {
        const Medium m = grid_medium({kLength, 3, 3}, ramp, kSigmaA, kSigmaS, factor);
        // From x = 3 to x = 30 along the ramp's row, and from outside the grid through all of it.
        expect_mean(
            [&](TrackingRng& r) {
                return grid_transmittance(m, {3, 1, 1}, {1, 0, 0}, 27.0f, r);
            },
            20000, 11, expected_transmittance(ramp_integral(3, 30)), "ratio tracking, part");
        expect_mean(
            [&](TrackingRng& r) {
                return grid_transmittance(m, {-5, 1, 1}, {1, 0, 0}, std::numeric_limits<float>::infinity(), r);
            },
            // The ramp, and its falls to the padding: 0 to 0.1 over [0, 1], 3.8 to 0 over [38, 39].
            20000, 12, expected_transmittance(ramp_integral(1, kLength - 2) + 0.05 + 1.9), "ratio tracking, whole");
    }
}

TEST(GridMedium, DeltaTrackingIsUnbiasedForWhatPassesAndWhatScatters) {
    // E[weight; no scattering] = T(end); E[weight; scattered] = ∫ T(t)·σ_s·d(t) dt.
    const double a = 3, length = 27;
    Vec3 scattered_expected;
    for (int c = 0; c < 3; ++c) {
        const double st = channel(kSigmaA + kSigmaS, c), ss = channel(kSigmaS, c);
        double sum = 0;
        constexpr int steps = 200000;
        for (int i = 0; i < steps; ++i) {
            const double x = a + (i + 0.5) * length / steps;
            sum += std::exp(-st * ramp_integral(a, x)) * ss * 0.1 * x * (length / steps);
        }
        (c == 0   ? scattered_expected.x
         : c == 1 ? scattered_expected.y
                  : scattered_expected.z) = static_cast<float>(sum);
    }
    for (const float factor : {1.0f, 2.0f}) {
        const Medium m = grid_medium({kLength, 3, 3}, ramp, kSigmaA, kSigmaS, factor);
        auto flight = [&](TrackingRng& r) {
            return sample_grid_free_flight(m, {3, 1, 1}, {1, 0, 0}, static_cast<float>(length), r);
        };
        expect_mean(
            [&](TrackingRng& r) {
                const FreeFlight f = flight(r);
                return f.scattered ? Vec3{0.0f} : f.weight;
            },
            40000, 21, expected_transmittance(ramp_integral(a, a + length)), "delta tracking, passing");
        expect_mean(
            [&](TrackingRng& r) {
                const FreeFlight f = flight(r);
                return f.scattered ? f.weight : Vec3{0.0f};
            },
            40000, 22, scattered_expected, "delta tracking, scattered");
    }
}

TEST(GridMedium, ARayMissingTheGridPassesUntouched) {
    const Medium m = grid_medium({kLength, 3, 3}, ramp, kSigmaA, kSigmaS);
    TrackingRng rng{5};
    EXPECT_EQ(grid_transmittance(m, {3, 10, 1}, {1, 0, 0}, 100.0f, rng), Vec3{1.0f});
    const FreeFlight f = sample_grid_free_flight(m, {3, 1, -4}, {0, 0, -1}, 100.0f, rng);
    EXPECT_FALSE(f.scattered);
    EXPECT_EQ(f.weight, Vec3{1.0f});
}

}  // namespace
}  // namespace sombra
