#include "denoise_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "denoise/denoise.h"
#include "image/image_io.h"

namespace sombra::bench {

void run_denoise_bench(const std::string& layers_file, const std::vector<int>& threads, int reps, std::ostream& out) {
    const ExrChannels exr = read_exr_channels(layers_file, denoise_channel_names());
    const DenoiseLayers layers = denoise_layers_from(exr.names, exr.values, exr.width, exr.height, layers_file);
    check_denoise_layers(layers, layers_file);
    const double megapixels = static_cast<double>(layers.width) * layers.height * 1e-6;
    out << "Denoiser on " << layers_file << " (" << layers.width << "x" << layers.height << "), median of " << reps
        << " runs:\n\n"
        << "| threads | s/MP (µs a pixel) | features | regressions | selection | second pass |\n"
        << "| ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const int t : threads) {
        std::vector<std::pair<double, DenoiseTimes>> runs;
        for (int r = 0; r < reps; ++r) {
            DenoiseTimes times;
            const auto start = std::chrono::steady_clock::now();
            const std::vector<float> image = denoise_image(layers, t, nullptr, &times);
            runs.emplace_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), times);
        }
        std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        const auto& [seconds, times] = runs[runs.size() / 2];
        char row[256];
        std::snprintf(row, sizeof row, "| %d | %.2f | %.2f | %.2f | %.2f | %.2f |\n", t, seconds / megapixels,
                      times.features / megapixels, times.regression / megapixels, times.selection / megapixels,
                      times.second_pass / megapixels);
        out << row;
    }
    out << "\n(stage columns in seconds per megapixel)\n";
}

}  // namespace sombra::bench
