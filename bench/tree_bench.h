// `sombra-bench tree`: the shape of sombra's BVH on the scenes' meshes, for
// judging a change to the builder by the tree it makes, free of timing
// noise: its SAH cost, size and (timed) build.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace sombra::bench {

// For each scene file, `reps` timed builds of make_bvh (median) and one
// Markdown table to `out`: build seconds, leaf references (a triangle
// counts once per leaf that holds it), wide nodes, triangle blocks, bytes,
// and the SAH cost of the wide tree and of the binary tree before the
// collapse (tree_bench.cpp). Throws Error for a scene that cannot be loaded.
void run_tree_bench(const std::vector<std::string>& scene_files, int reps, std::ostream& out);

}  // namespace sombra::bench
