// `sombra-bench growth`: build time, render time and memory against triangle
// count, over a series of meshes of one model at growing resolution.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "bench_util.h"

namespace sombra::bench {

struct GrowthOptions {
    int reps = 3;
    int width = 640, height = 360;  // the quick look's image (spp 1)
    std::string csv;                // also write the numbers here, one line per mesh and backend; "" = no
    EmbreeSettings embree = {};
};

// For each model file (.obj or .ply): the quick-look scene of spec §7 (one
// view framing the model, three point lights), measured as in measure.h.
// Writes one Markdown table to `out`: triangles, load seconds, and per
// backend build and render seconds, structure megabytes and bytes per
// triangle, the process's peak RSS while loading and while each backend
// built and rendered (mesh included), and its peak RSS so far. Throws Error
// on a bad file or disagreeing images.
void run_growth_bench(const std::vector<std::string>& model_files, const GrowthOptions& options, std::ostream& out);

}  // namespace sombra::bench
