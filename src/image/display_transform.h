// Linear radiance → the 8-bit sRGB of a PNG or JPEG (spec §1, §27):
// exposure, then a tone mapper, then the sRGB transfer function.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "core/vec3.h"
#include "image/image_io.h"

namespace sombra {

// The tone mapper named `name` ("none", "pbr-neutral"); throws
// Error("--tonemap", …) for any other name.
Tonemap tonemap_option(std::string_view name);
std::string_view tonemap_name(Tonemap tonemap);

// Khronos PBR Neutral (start of compression 0.8 − 0.04, desaturation 0.15)
// of one linear RGB value; the result is in [0, 1] for inputs ≥ 0.
Vec3 pbr_neutral(Vec3 linear);

// 8-bit sRGB RGB bytes of `image` under `display`, row-major, top row
// first; pixels with a non-finite channel are black.
std::vector<std::uint8_t> display_bytes(ImageView image, DisplayTransform display);

}  // namespace sombra
