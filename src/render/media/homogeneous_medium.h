// Light along a straight segment through a homogeneous medium (spec §26),
// in closed form per channel: what survives (transmittance), what the
// medium emits on the way, and where a path interacts with it. A coloured
// medium samples distances by spectral MIS: a channel chosen uniformly, the
// distance from that channel's exponential, and the weights divided by the
// mean of the three channels' densities (the one-sample balance heuristic),
// so that no channel's estimate blows up where another's extinction differs.
#pragma once

#include "core/vec3.h"
#include "scene/medium.h"

namespace sombra {

// exp(−σ_t·d) per channel. `distance` may be +∞: then 1 where σ_t is 0, else 0.
Vec3 homogeneous_transmittance(const Medium& medium, float distance);

// The radiance the medium emits along `distance` and that reaches its start:
// ∫₀ᵈ exp(−σ_t·s)·ε ds = ε·(1 − exp(−σ_t·d))/σ_t per channel (ε·d where σ_t is 0).
Vec3 homogeneous_emission(const Medium& medium, float distance);

struct FreeFlight {
    bool scattered = false;  // the path interacts with the medium at `t`, before the segment's end
    float t = 0.0f;          // where: the distance from the segment's start
    // What the path's throughput is multiplied by: if scattered,
    // T(t)·σ_s / p(t) (the absorbed share leaves the path); else
    // T(end) / P(no interaction before the end).
    Vec3 weight{1.0f};
};

// Samples where a path first interacts with the medium on a segment of
// length `end` (+∞ for a ray that leaves the scene), from two numbers in
// [0, 1). Unbiased: E[weight · f] over both outcomes is the transmittance-
// weighted integral a path tracer needs (tests: homogeneous_medium_test).
FreeFlight sample_homogeneous_free_flight(const Medium& medium, float end, float u_channel, float u_distance);

}  // namespace sombra
