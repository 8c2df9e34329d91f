#include "render/media/grid_medium.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sombra {

namespace {

float component(Vec3 v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }
float mean(Vec3 v) { return (v.x + v.y + v.z) / 3.0f; }

// Visits the majorant cells a ray crosses, in order, as segments [t0, t1)
// of its distance with the largest extinction σ̄ that the cell allows
// (amanatides–Woo's traversal in the grid's dense coordinates).
// visit(t0, t1, sigma_bar, q0, dq) returns false to stop.
template <class Visit>
void march_majorants(const Medium& medium, Vec3 origin, Vec3 dir, float end, Visit visit) {
    const DensityGrid& grid = *medium.density;
    const Vec3 q0 = transform_point(medium.world_to_grid, origin);
    const Vec3 dq = transform_vector(medium.world_to_grid, dir);
    // Clip to the box [0, dims − 1] where the density may be non-zero.
    float t_in = 0.0f, t_out = end;
    for (int a = 0; a < 3; ++a) {
        const float o = component(q0, a), d = component(dq, a), hi = static_cast<float>(grid.dims[a] - 1);
        if (d == 0.0f) {
            if (!(o >= 0.0f && o <= hi)) return;
            continue;
        }
        float t0 = (0.0f - o) / d, t1 = (hi - o) / d;
        if (t0 > t1) std::swap(t0, t1);
        t_in = std::max(t_in, t0);
        t_out = std::min(t_out, t1);
    }
    if (!(t_in < t_out)) return;
    const float sigma_t_max = max_component(medium.sigma_a + medium.sigma_s);
    const auto block = static_cast<float>(kMajorantBlock);
    // The cell at the entry point, and the DDA's steps.
    int cell[3], step[3];
    float t_next[3], t_delta[3];
    const Vec3 entry = q0 + dq * t_in;
    for (int a = 0; a < 3; ++a) {
        const float d = component(dq, a);
        cell[a] = std::clamp(static_cast<int>(std::floor(component(entry, a) / block)), 0, grid.cells[a] - 1);
        if (d > 0.0f) {
            step[a] = 1;
            t_next[a] = (static_cast<float>(cell[a] + 1) * block - component(q0, a)) / d;
            t_delta[a] = block / d;
        } else if (d < 0.0f) {
            step[a] = -1;
            t_next[a] = (static_cast<float>(cell[a]) * block - component(q0, a)) / d;
            t_delta[a] = -block / d;
        } else {
            step[a] = 0;
            t_next[a] = std::numeric_limits<float>::infinity();
            t_delta[a] = std::numeric_limits<float>::infinity();
        }
    }
    const auto cx = static_cast<std::size_t>(grid.cells[0]), cy = static_cast<std::size_t>(grid.cells[1]);
    float t = t_in;
    while (t < t_out) {
        const int a = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
        const float t1 = std::min(t_next[a], t_out);
        const float majorant =
            grid.majorants[static_cast<std::size_t>(cell[0]) + static_cast<std::size_t>(cell[1]) * cx +
                           static_cast<std::size_t>(cell[2]) * cx * cy];
        if (t1 > t && !visit(t, t1, majorant * sigma_t_max, q0, dq)) return;
        t = std::max(t, t1);
        cell[a] += step[a];
        if (cell[a] < 0 || cell[a] >= grid.cells[a]) return;
        t_next[a] += t_delta[a];
    }
}

}  // namespace

FreeFlight sample_grid_free_flight(const Medium& medium, Vec3 origin, Vec3 dir, float end, TrackingRng& rng) {
    FreeFlight flight;
    int steps = 0;
    const DensityGrid& grid = *medium.density;
    march_majorants(medium, origin, dir, end, [&](float t0, float t1, float sigma_bar, Vec3 q0, Vec3 dq) {
        if (!(sigma_bar > 0.0f)) return true;
        for (float t = t0;;) {
            t += -std::log1p(-rng.next()) / sigma_bar;
            if (!(t < t1)) return true;
            if (++steps > kMaxTrackingSteps) {
                flight.weight = Vec3{0.0f};
                return false;
            }
            const float d = density_at(grid, q0 + dq * t);
            const Vec3 sigma_a = medium.sigma_a * d, sigma_s = medium.sigma_s * d;
            const Vec3 sigma_n = max(Vec3{sigma_bar} - sigma_a - sigma_s, Vec3{0.0f});
            const float pa = mean(sigma_a), ps = mean(sigma_s), pn = mean(sigma_n);
            const float u = rng.next() * (pa + ps + pn);
            if (u < pa) {  // absorbed: the path ends (grid media emit nothing)
                flight.weight = Vec3{0.0f};
                return false;
            }
            if (u < pa + ps) {
                flight.scattered = true;
                flight.t = t;
                flight.weight = flight.weight * sigma_s * ((pa + ps + pn) / (sigma_bar * ps));
                return false;
            }
            flight.weight = flight.weight * sigma_n * ((pa + ps + pn) / (sigma_bar * pn));
        }
    });
    return flight;
}

Vec3 grid_transmittance(const Medium& medium, Vec3 origin, Vec3 dir, float end, TrackingRng& rng) {
    Vec3 transmittance{1.0f};
    int steps = 0;
    const DensityGrid& grid = *medium.density;
    const Vec3 sigma_t = medium.sigma_a + medium.sigma_s;
    march_majorants(medium, origin, dir, end, [&](float t0, float t1, float sigma_bar, Vec3 q0, Vec3 dq) {
        if (!(sigma_bar > 0.0f)) return true;
        for (float t = t0;;) {
            t += -std::log1p(-rng.next()) / sigma_bar;
            if (!(t < t1)) return true;
            if (++steps > kMaxTrackingSteps) {
                transmittance = Vec3{0.0f};
                return false;
            }
            const float d = density_at(grid, q0 + dq * t);
            transmittance = transmittance * max(Vec3{1.0f} - sigma_t * (d / sigma_bar), Vec3{0.0f});
            // Russian roulette once little is left: survivors keep the expected value.
            constexpr float kRouletteBelow = 0.05f;
            const float largest = max_component(transmittance);
            if (largest < kRouletteBelow) {
                const float q = largest / kRouletteBelow;
                if (!(rng.next() < q)) {
                    transmittance = Vec3{0.0f};
                    return false;
                }
                transmittance = transmittance / q;
            }
        }
    });
    return transmittance;
}

}  // namespace sombra
