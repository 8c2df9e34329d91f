// `sombra-bench denoise`: the denoiser's time on the layers of an EXR file
// (sombra render --aov denoise), stage by stage, at several thread counts.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace sombra::bench {

// For each thread count, `reps` runs of denoise_image (the median run
// reported): one Markdown table to `out` with seconds per megapixel in all
// and per stage, and µs per pixel. Throws Error for a file without the layers.
void run_denoise_bench(const std::string& layers_file, const std::vector<int>& threads, int reps, std::ostream& out);

}  // namespace sombra::bench
