// `sombra-bench path` and `sombra-bench path-error`: the path integrator
// (spec §10) under incoherent rays, bvh against embree, and its error
// against a converged reference at equal time and at fixed sample counts.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bench_util.h"

namespace sombra::bench {

struct PathBenchOptions {
    int reps = 5;     // timed renders per backend, alternating; medians reported
    int width = 192;  // image size (overrides the scenes)
    int height = 192;
    int spp = 16;
    int max_depth = 8;
    EmbreeSettings embree = {};
};

// Renders each scene with the path integrator (integrator = path set here,
// the scene files stay version 1) with every compared backend. Before any
// timing it checks, per scene:
//  - bvh against embree: the two images must have the same mean radiance
//    (a paired test: per pixel d = bvh − embree, whose mean over the image
//    must lie within kMaxZ standard errors of 0 in every channel; see
//    path_bench.cpp for why not pixel by pixel);
//  - bvh against brute: whole paths (1 spp) at a sample of pixels, traced
//    through the BVH and the brute-force loop, must give the same radiance
//    (the BVH's hits are bit-identical to brute's, so the paths are too).
// Then `reps` renders per backend, alternating, over structures built once.
// One Markdown table to `out`: per scene a row per backend (render seconds,
// rays, Mrays/s, samples/s, share of pixels equal) and a row of ratios.
void run_path_bench(const std::vector<std::string>& scene_files, const PathBenchOptions& options, std::ostream& out);

struct PathErrorOptions {
    int width = 128;
    int height = 128;
    int max_depth = 8;
    int reference_spp = 4096;
    std::vector<int> fixed_spp{16, 64, 256};
    double budget_seconds = 1.0;           // the equal-time render's budget
    std::vector<double> noise_thresholds;  // adaptive renders (--noise-threshold), up to the largest fixed spp
    std::filesystem::path cache_dir = "build/bench";  // where the reference is kept
};

// Renders (or reads from cache_dir) a reference of `scene_file` at
// reference_spp with seed 1 and the BVH, then renders with seed 0 at each of
// fixed_spp, in passes until budget_seconds, and adaptively at each of
// noise_thresholds, and writes one Markdown
// table of RMSE and relative MSE against the reference (see path_bench.cpp
// for the exact definitions) to `out`.
void run_path_error_bench(const std::string& scene_file, const PathErrorOptions& options, std::ostream& out);

}  // namespace sombra::bench
