// What the denoiser reads (spec §25): each pixel's colour as the means of
// its even- and odd-indexed samples (the half buffers A and B), the
// variance of its mean from its own samples, and the first surface's
// albedo, normal and depth per half. The render gathers them with
// `--aov denoise` or `--denoise`; an EXR file carries them under the names
// denoise_channels gives, so `sombra denoise` reads back exactly what the
// render had.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace sombra {

struct DenoiseLayers {
    int width = 0, height = 0;
    std::array<std::vector<float>, 2> color;   // 3 a pixel: half A (even samples), half B (odd)
    std::vector<float> variance;               // 3 a pixel: the variance of the pixel's mean
    std::array<std::vector<float>, 2> albedo;  // 3 a pixel, per half (a miss adds 0)
    std::array<std::vector<float>, 2> normal;  // 3 a pixel, per half (a miss adds 0)
    std::array<std::vector<float>, 2> depth;   // 1 a pixel, per half: mean over the hits, +∞ with none
};

// Calls visit(name, values, component, stride) for every channel the
// denoiser reads, named as EXR files carry them: variance.R/G/B,
// denoise.A.R/G/B, denoise.B.R/G/B, denoise.albedoA.R/G/B,
// denoise.albedoB.R/G/B, denoise.normalA.X/Y/Z, denoise.normalB.X/Y/Z,
// denoise.depthA.Z, denoise.depthB.Z. The channel is values[p · stride +
// component] for pixel p. `Layers`: DenoiseLayers, const or not.
template <typename Layers, typename Visit>
void for_each_denoise_channel(Layers& layers, Visit visit) {
    auto visit3 = [&visit](const std::string& layer, const char* axes, auto& values) {
        for (int c = 0; c < 3; ++c) visit(layer + "." + axes[c], values, c, 3);
    };
    const char* const half[2] = {"A", "B"};
    visit3("variance", "RGB", layers.variance);
    for (int h = 0; h < 2; ++h) visit3(std::string("denoise.") + half[h], "RGB", layers.color[h]);
    for (int h = 0; h < 2; ++h) visit3(std::string("denoise.albedo") + half[h], "RGB", layers.albedo[h]);
    for (int h = 0; h < 2; ++h) visit3(std::string("denoise.normal") + half[h], "XYZ", layers.normal[h]);
    for (int h = 0; h < 2; ++h) visit(std::string("denoise.depth") + half[h] + ".Z", layers.depth[h], 0, 1);
}

// The names for_each_denoise_channel gives, in its order: what a reader
// of the layers asks an EXR file for.
std::vector<std::string> denoise_channel_names();

// The layers from named channels of width × height floats each (an EXR
// file's), taken from `values`. Throws Error(where, "no layer 'NAME' ...")
// for the first channel the denoiser reads that `names` lacks.
DenoiseLayers denoise_layers_from(const std::vector<std::string>& names, const std::vector<std::vector<float>>& values,
                                  int width, int height, const std::string& where);

// The largest values the denoiser takes: beyond them its squares and sums
// would overflow a float (no render comes near them).
inline constexpr float kMaxDenoiseColour = 1e12f;
inline constexpr float kMaxDenoiseVariance = 1e24f;
inline constexpr float kMaxDenoiseFeature = 1e6f;

// Throws Error(where, what) when a layer is not width × height pixels, a
// colour is not in [0, kMaxDenoiseColour], a variance not in
// [0, kMaxDenoiseVariance] or +inf (one sample), an albedo or normal not
// within ±kMaxDenoiseFeature, or a depth NaN or -inf (+inf: no hit)
// (`where`: the file the layers came from).
void check_denoise_layers(const DenoiseLayers& layers, const std::string& where);

}  // namespace sombra
