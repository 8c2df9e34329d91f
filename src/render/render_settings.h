// How to render (spec §2 "render", §10, §12): image size, samples, seed,
// integrator and texture filter. The scene file's "render" section is read
// into these (io/scene_json/scene_file.h returns them beside the Scene), and
// front ends override them (api/render_options.h). Header-only: it is the
// one render/ header the readers include, and they need not link the renderer.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/image_limits.h"

namespace sombra {

// Which estimator computes each sample (spec §10).
enum class IntegratorKind {
    Direct,  // point lights' direct light, emission and background seen (spec §4)
    Path,    // the whole rendering equation by path tracing
};

// How material textures are looked up (spec §12).
enum class TextureFilter {
    Bilinear,  // the default: bilinear at full resolution for every ray; supersampling antialiases
    Mipmap,    // trilinear in a mip pyramid at the level of the camera ray's cone footprint (render/ray_cone.h)
};

// The names scene files, the command line, Python and explain use for them.
constexpr std::string_view integrator_name(IntegratorKind kind) {
    return kind == IntegratorKind::Path ? "path" : "direct";
}
constexpr std::string_view texture_filter_name(TextureFilter filter) {
    return filter == TextureFilter::Mipmap ? "mipmap" : "bilinear";
}
constexpr std::optional<IntegratorKind> parse_integrator(std::string_view name) {
    if (name == "direct") return IntegratorKind::Direct;
    if (name == "path") return IntegratorKind::Path;
    return std::nullopt;
}
constexpr std::optional<TextureFilter> parse_texture_filter(std::string_view name) {
    if (name == "bilinear") return TextureFilter::Bilinear;
    if (name == "mipmap") return TextureFilter::Mipmap;
    return std::nullopt;
}

struct RenderSettings {
    int width = 640;
    int height = 480;
    int spp = 1;
    std::uint64_t seed = 0;
    IntegratorKind integrator = IntegratorKind::Direct;
    int max_depth = 8;  // path: the most scattering events on a path, 0 … kMaxDepth
    // path: the most scattering events in media on a path (spec §26), 0 … kMaxVolumeDepth
    int max_volume_depth = 256;
    // Mipmap needs the textures' pyramids (build_mip_pyramids, scene/texture_mipmap.h)
    // built before rendering; without them lookups stay at full resolution.
    TextureFilter texture_filter = TextureFilter::Bilinear;
};

// Limits on what a render may ask for beside the image's size
// (core/image_limits.h): a billion samples is a mistake, not a request. The
// scene file reader and the command-line overrides check the same numbers.
inline constexpr int kMaxSpp = 65536;
inline constexpr int kMaxDepth = 1024;
inline constexpr int kMaxVolumeDepth = 65536;

// "" when the settings lie within the limits above, else a short message
// naming the offending field, e.g. "width must be between 1 and 32768".
inline std::string render_settings_problem(const RenderSettings& r) {
    const std::string side_range = " must be between 1 and " + std::to_string(kMaxImageSide);
    if (r.width < 1 || r.width > kMaxImageSide) return "width" + side_range;
    if (r.height < 1 || r.height > kMaxImageSide) return "height" + side_range;
    if (r.spp < 1 || r.spp > kMaxSpp) return "spp must be between 1 and " + std::to_string(kMaxSpp);
    if (r.max_depth < 0 || r.max_depth > kMaxDepth)
        return "max_depth must be between 0 and " + std::to_string(kMaxDepth);
    if (r.max_volume_depth < 0 || r.max_volume_depth > kMaxVolumeDepth)
        return "max_volume_depth must be between 0 and " + std::to_string(kMaxVolumeDepth);
    const std::int64_t pixels = std::int64_t{r.width} * r.height;
    if (pixels > kMaxPixels)
        return "image of " + std::to_string(r.width) + "x" + std::to_string(r.height) +
               " pixels exceeds the limit of " + std::to_string(kMaxPixels) + " pixels";
    return {};
}

}  // namespace sombra
