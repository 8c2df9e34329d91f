// Light along a straight segment through a grid medium (spec §26), by
// null-collision tracking against the majorant grid (scene/density_grid.h):
// where a path scatters (delta tracking) and what a shadow ray keeps
// (ratio tracking). Both are unbiased for any majorant that bounds the
// density, and draw a varying count of numbers from a TrackingRng.
#pragma once

#include <cstdint>

#include "core/vec3.h"
#include "render/media/homogeneous_medium.h"
#include "scene/medium.h"

namespace sombra {

// The numbers the tracking estimators draw, as many as they need: a
// splitmix64 stream seeded per camera sample, so that an image is the
// same on any thread count.
struct TrackingRng {
    std::uint64_t state = 0;
    float next() {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
        return static_cast<float>(z >> 40) * 0x1p-24f;  // in [0, 1)
    }
};

// A tracked segment gives up after this many tentative collisions (the
// path is then absorbed, the shadow ray blocked): a bound on the work of a
// ray through a medium scaled to absurd densities (σ̄·length > 65536).
inline constexpr int kMaxTrackingSteps = 1 << 16;

// Where a path leaving `origin` along the unit direction `dir` first
// scatters in grid medium `medium` before `end` (+∞: no surface ahead),
// by delta tracking: tentative collisions at the majorant's rate, each
// absorbing, scattering or null with probabilities from the three
// channels' mean coefficients, the weights correcting each channel.
// weight 0: absorbed.
FreeFlight sample_grid_free_flight(const Medium& medium, Vec3 origin, Vec3 dir, float end, TrackingRng& rng);

// The transmittance of grid medium `medium` from `origin` along the unit
// direction `dir` over `end` (+∞ allowed), by ratio tracking with Russian
// roulette once it is small.
Vec3 grid_transmittance(const Medium& medium, Vec3 origin, Vec3 dir, float end, TrackingRng& rng);

}  // namespace sombra
