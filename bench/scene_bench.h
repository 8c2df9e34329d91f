// `sombra-bench scenes`: every scene rendered with bvh and embree, one table.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bench_util.h"

namespace sombra::bench {

struct SceneBenchOptions {
    int reps = 5;
    std::optional<int> width, height;  // override the scenes' own image size
    EmbreeSettings embree = {};
};

// Measures each scene file (measure.h) and writes one Markdown table to
// `out`: per scene a row per backend (triangles, build and render seconds,
// Mrays/s counting camera and shadow rays, structure bytes per triangle,
// share of pixels equal to bvh's) and a row of bvh/embree ratios. Progress
// goes to stderr. Throws Error for a scene that cannot be loaded or whose
// images disagree.
void run_scene_bench(const std::vector<std::string>& scene_files, const SceneBenchOptions& options, std::ostream& out);

}  // namespace sombra::bench
