// `sombra denoise IN.exr -o OUT` (spec §25): the layers `render --aov
// denoise` wrote, denoised as `render --denoise` would, and one summary line.
#include <chrono>
#include <iostream>
#include <string>
#include <vector>

#include "app/report.h"
#include "app/run.h"
#include "denoise/denoise.h"
#include "image/image_io.h"

namespace sombra {

int run_denoise(const CliOptions& o) {
    return reporting_errors(o.input, [&] {
        check_output_path(o.output);
        // The file's channels are let go once copied into the layers: a large frame's peak is lower.
        const DenoiseLayers layers = [&] {
            const ExrChannels exr = read_exr_channels(o.input, denoise_channel_names());
            return denoise_layers_from(exr.names, exr.values, exr.width, exr.height, o.input);
        }();
        check_denoise_layers(layers, o.input);
        const auto start = std::chrono::steady_clock::now();
        const std::vector<float> image = denoise_image(layers, o.render.threads);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        write_image(o.output, ImageView{layers.width, layers.height, image.data()}, o.display);
        if (!o.quiet) {
            char took[32];
            std::snprintf(took, sizeof took, "%.2f s", seconds);
            std::cerr << "sombra: denoised " << one_line_message(o.input) << " (" << layers.width << "x"
                      << layers.height << ") in " << took << " | wrote " << one_line_message(o.output) << '\n';
        }
        return 0;
    });
}

}  // namespace sombra
