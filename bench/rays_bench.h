// `sombra-bench rays`: traversal alone under incoherent rays, bvh against
// embree, on identical batches of rays leaving the scene's surfaces.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "bench_util.h"

namespace sombra::bench {

struct RaysBenchOptions {
    int reps = 9;       // timed rounds, the backends in rotated order; medians reported
    int rays = 400000;  // rays of each kind per round
    EmbreeSettings embree = {};
};

// Per scene, two batches made once with a fixed seed: from a point of a
// random triangle (uniform over triangles, then over the triangle), a
// closest-hit ray in a uniformly random direction on the side of the
// triangle's normal, and a shadow ray to the scene's point lights in turn
// (t in (0, 1), as the integrators trace them; to a random point of the
// scene's box when it has none). Before timing, the BVH must give the
// brute-force loop's answers, bit for bit, on a sample of both batches.
// One Markdown table to `out`: per scene and kind the seconds per backend,
// Mrays/s and the bvh ÷ embree time.
void run_rays_bench(const std::vector<std::string>& scene_files, const RaysBenchOptions& options, std::ostream& out);

}  // namespace sombra::bench
