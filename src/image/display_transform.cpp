#include "image/display_transform.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "image/srgb8_table.h"
#include "image/writers.h"

namespace sombra {

Tonemap tonemap_option(std::string_view name) {
    if (name == "none") return Tonemap::None;
    if (name == "pbr-neutral") return Tonemap::PbrNeutral;
    throw Error("--tonemap", "expected none or pbr-neutral, not '" + std::string(name) + "'");
}

std::string_view tonemap_name(Tonemap tonemap) { return tonemap == Tonemap::None ? "none" : "pbr-neutral"; }

Vec3 pbr_neutral(Vec3 c) {
    // The Khronos PBR Neutral specification's constants and steps.
    constexpr float start_compression = 0.8f - 0.04f;
    constexpr float desaturation = 0.15f;
    const float x = std::min(c.x, std::min(c.y, c.z));
    const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    c = c - Vec3{offset};
    const float peak = std::max(c.x, std::max(c.y, c.z));
    if (peak < start_compression) return c;
    constexpr float d = 1.0f - start_compression;
    const float new_peak = 1.0f - d * d / (peak + d - start_compression);
    c = c * (new_peak / peak);
    const float g = 1.0f - 1.0f / (desaturation * (peak - new_peak) + 1.0f);
    return c * (1.0f - g) + Vec3{new_peak * g};
}

std::vector<std::uint8_t> display_bytes(ImageView image, DisplayTransform display) {
    const auto pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    const float scale = std::exp2(display.exposure);
    const Srgb8Table srgb;  // ~1 ms to build; encode_srgb8's codes without its pow()
    std::vector<std::uint8_t> bytes(pixels * 3);
    for (std::size_t pixel = 0; pixel < pixels; ++pixel) {
        if (!pixel_is_finite(image.rgb, pixel)) continue;  // stays black
        const float* p = image.rgb + 3 * pixel;
        Vec3 v{p[0] * scale, p[1] * scale, p[2] * scale};
        if (display.tonemap == Tonemap::PbrNeutral) v = pbr_neutral(max(v, Vec3{0.0f}));
        bytes[3 * pixel + 0] = srgb.encode(v.x);
        bytes[3 * pixel + 1] = srgb.encode(v.y);
        bytes[3 * pixel + 2] = srgb.encode(v.z);
    }
    return bytes;
}

}  // namespace sombra
