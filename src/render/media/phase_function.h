// The Henyey–Greenstein phase function (spec §26): how a medium scatters
// light, as a density over the direction it leaves in, given the direction
// it travelled in. One parameter, the mean cosine g in (−1, 1): 0 scatters
// evenly, g > 0 forward (fog, clouds), g < 0 back.
#pragma once

#include "core/vec3.h"

namespace sombra {

// The density, per steradian, of leaving along `out` after travelling along
// `in`, as a function of cos θ = dot(in, out) (both unit vectors):
// (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}). It integrates to 1 over the
// sphere, and is symmetric: swapping in and out changes nothing.
float henyey_greenstein(float g, float cos_theta);

struct PhaseSample {
    Vec3 out;          // the new direction of travel, unit length
    float pdf = 0.0f;  // its density, which is the phase function's value (sampled exactly)
};

// Samples `out` in proportion to henyey_greenstein(g, dot(in, out)) from two
// numbers in [0, 1), by inverting the distribution of cos θ; `in` is unit.
PhaseSample sample_henyey_greenstein(float g, Vec3 in, float u1, float u2);

}  // namespace sombra
