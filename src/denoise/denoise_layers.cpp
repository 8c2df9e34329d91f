#include "denoise/denoise_layers.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "core/error.h"
#include "core/format.h"

namespace sombra {

std::vector<std::string> denoise_channel_names() {
    std::vector<std::string> names;
    const DenoiseLayers none;
    for_each_denoise_channel(none, [&names](const std::string& name, auto&&...) { names.push_back(name); });
    return names;
}

DenoiseLayers denoise_layers_from(const std::vector<std::string>& names, const std::vector<std::vector<float>>& values,
                                  int width, int height, const std::string& where) {
    DenoiseLayers layers;
    layers.width = width;
    layers.height = height;
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    for_each_denoise_channel(layers, [&](const std::string& name, std::vector<float>& target, int component,
                                         int stride) {
        const auto found = std::find(names.begin(), names.end(), name);
        if (found == names.end())
            throw Error(where, "no layer '" + name + "': the denoiser reads what sombra render --aov denoise writes");
        const std::vector<float>& channel = values[static_cast<std::size_t>(found - names.begin())];
        if (channel.size() != pixels)
            throw Error(where, name + ": " + std::to_string(channel.size()) + " values, not " + std::to_string(pixels));
        const auto step = static_cast<std::size_t>(stride);
        target.resize(pixels * step);
        for (std::size_t p = 0; p < pixels; ++p) target[p * step + static_cast<std::size_t>(component)] = channel[p];
    });
    return layers;
}

void check_denoise_layers(const DenoiseLayers& layers, const std::string& where) {
    if (layers.width < 1 || layers.height < 1)
        throw Error(where, "the denoiser needs an image of at least 1 × 1 pixels");
    const std::size_t pixels = static_cast<std::size_t>(layers.width) * static_cast<std::size_t>(layers.height);
    for_each_denoise_channel(layers, [&](const std::string& name, const std::vector<float>& values, int component,
                                         int stride) {
        const auto step = static_cast<std::size_t>(stride);
        if (values.size() != pixels * step)
            throw Error(where, name + ": " + std::to_string(values.size() / step) + " pixels, not " +
                                   std::to_string(pixels) + " (" + std::to_string(layers.width) + " × " +
                                   std::to_string(layers.height) + ")");
        const bool colour = name.starts_with("denoise.A.") || name.starts_with("denoise.B.");
        const bool variance = name.starts_with("variance.");
        const bool depth = name.starts_with("denoise.depth");
        for (std::size_t p = 0; p < pixels; ++p) {
            const float v = values[p * step + static_cast<std::size_t>(component)];
            // Beyond these bounds the passes' squares and sums would overflow a float.
            const bool bad = std::isnan(v) || (colour && !(v >= 0.0f && v <= kMaxDenoiseColour)) ||
                             (variance && !(v >= 0.0f && (v <= kMaxDenoiseVariance || std::isinf(v)))) ||
                             (depth && v == -std::numeric_limits<float>::infinity()) ||
                             (!colour && !variance && !depth && !(std::abs(v) <= kMaxDenoiseFeature));
            if (!bad) continue;
            const auto x = static_cast<int>(p % static_cast<std::size_t>(layers.width));
            const auto y = static_cast<int>(p / static_cast<std::size_t>(layers.width));
            throw Error(where, name + ": " + format_number(v) + " at pixel (" + std::to_string(x) + ", " +
                                   std::to_string(y) + ") " +
                                   (colour     ? "is not a colour from 0 to 1e12"
                                    : variance ? "is not a variance from 0 to 1e24 (or +inf)"
                                    : depth    ? "is not a depth"
                                               : "is not a feature from -1e6 to 1e6"));
        }
    });
}

}  // namespace sombra
