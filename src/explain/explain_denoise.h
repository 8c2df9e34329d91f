// What `explain --denoise` adds to the text and the picture (spec §25),
// each told apart from spec §14's story so that either stays readable.
// Internal to explain/: explain_text and explain_svg call these.
#pragma once

#include <string>

#include "explain/explain.h"

namespace sombra {

// The terms the text lists, the largest first.
inline constexpr std::size_t kDenoiseTextTerms = 10;

// The text's last section: pixel (x, y) raw and denoised, Σ w·c before the
// clamp, how many terms from which pixels, the weights' sums per channel,
// and the kDenoiseTextTerms largest terms by |w·c| summed over the channels.
std::string denoise_text(const DenoiseStory& story, int x, int y);

// The width the weight map takes in the picture, its legend included; its
// height is at most explain_svg's panel (480).
inline constexpr float kDenoiseMapWidth = 320.0f;

// The weights around pixel (x, y) as SVG elements with their top-left at
// (left, top): each pixel of the terms' bounding box coloured by its weight
// (both halves, the mean over R, G, B; positive red, negative blue, white
// 0, the strength as √|w|), the pixel outlined, a scale and a caption below.
std::string denoise_weight_map(const DenoiseStory& story, int x, int y, float left, float top);

}  // namespace sombra
