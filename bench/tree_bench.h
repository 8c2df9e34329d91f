// `sombra-bench tree`: the BVH's tree at each build quality, side by side:
// its SAH cost, size and build time, on the scenes' meshes.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "accel/bvh.h"

namespace sombra::bench {

// For each scene file, builds sombra's BVH at Fast and at High quality
// (`reps` timed builds each, alternating, medians), and writes one Markdown
// table to `out`: build seconds, leaf references (a triangle counts once
// per leaf that holds it), wide nodes, triangle blocks, bytes, and the
// tree's SAH cost (bvh_sah_cost). Throws Error for a scene that cannot be
// loaded.
// `high` is what High stands for (bvh_build_options) unless the command
// line changes its α or budget.
void run_tree_bench(const std::vector<std::string>& scene_files, int reps, const BvhBuildOptions& high,
                    std::ostream& out);

}  // namespace sombra::bench
