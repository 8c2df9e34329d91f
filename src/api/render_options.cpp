#include "api/render_options.h"

#include <string>

#include "core/error.h"
#include "core/format.h"

namespace sombra {

namespace {

void check_positive(const char* option, const std::optional<double>& value, double most) {
    if (value && !(*value > 0.0 && *value <= most))
        throw Error(option, "must be a number above 0 and at most " + std::to_string(static_cast<long long>(most)) +
                                ", not " + format_number(*value));
}

}  // namespace

void check_render_options(const RenderOptions& o) {
    if (o.threads < 0 || o.threads > kMaxThreads)
        throw Error("--threads",
                    "must be between 0 and " + std::to_string(kMaxThreads) + ", not " + std::to_string(o.threads));
    if (o.frame && (*o.frame < 0 || *o.frame > kMaxFrame))
        throw Error("--frame",
                    "must be between 0 and " + std::to_string(kMaxFrame) + ", not " + std::to_string(*o.frame));
    if (o.overrides.max_depth && (*o.overrides.max_depth < 0 || *o.overrides.max_depth > kMaxDepth))
        throw Error("--max-depth", "must be between 0 and " + std::to_string(kMaxDepth) + ", not " +
                                       std::to_string(*o.overrides.max_depth));
    if (o.overrides.max_volume_depth &&
        (*o.overrides.max_volume_depth < 0 || *o.overrides.max_volume_depth > kMaxVolumeDepth))
        throw Error("--max-volume-depth", "must be between 0 and " + std::to_string(kMaxVolumeDepth) + ", not " +
                                              std::to_string(*o.overrides.max_volume_depth));
    if (o.aovs.noisy && !o.denoise) throw Error("--aov", "noisy is the image before denoising: it needs --denoise");
    check_positive("--time", o.time_budget, kMaxTimeBudget);
    check_positive("--noise-threshold", o.noise_threshold, kMaxNoiseThreshold);
    if (o.min_spp < 1 || o.min_spp > kMaxSpp)
        throw Error("--min-spp",
                    "must be between 1 and " + std::to_string(kMaxSpp) + ", not " + std::to_string(o.min_spp));
}

RenderSettings resolve_settings(const RenderSettings& scene_settings, const SettingOverrides& o) {
    RenderSettings s = scene_settings;
    auto check = [&s](const char* option) {
        if (const std::string problem = render_settings_problem(s); !problem.empty()) throw Error(option, problem);
    };
    if (o.width) {
        s.width = *o.width;
        check("--width");
    }
    if (o.height) {
        s.height = *o.height;
        check("--height");
    }
    if (o.spp) {
        s.spp = *o.spp;
        check("--spp");
    }
    if (o.seed) s.seed = *o.seed;
    if (o.integrator) s.integrator = *o.integrator;
    if (o.max_depth) {
        s.max_depth = *o.max_depth;
        check("--max-depth");
    }
    if (o.max_volume_depth) {
        s.max_volume_depth = *o.max_volume_depth;
        check("--max-volume-depth");
    }
    if (o.texture_filter) s.texture_filter = *o.texture_filter;
    return s;
}

RenderSettings resolve_render_settings(const RenderSettings& scene_settings, const RenderOptions& o) {
    RenderSettings s = resolve_settings(scene_settings, o.overrides);
    if (o.time_budget && !o.overrides.spp) s.spp = kMaxSpp;
    if (o.denoise && s.spp < 2)
        throw UsageError("--denoise", "needs at least 2 samples per pixel, and the render takes " +
                                          std::to_string(s.spp) + " (raise --spp)");
    if (const std::optional<PixelWindow>& c = o.crop) {
        const std::int64_t x1 = std::int64_t{c->x0} + c->width, y1 = std::int64_t{c->y0} + c->height;
        if (c->x0 < 0 || c->width < 1 || x1 > s.width || c->y0 < 0 || c->height < 1 || y1 > s.height)
            throw Error("--crop", "expected X0 Y0 X1 Y1 with 0 <= X0 < X1 <= " + std::to_string(s.width) +
                                      " and 0 <= Y0 < Y1 <= " + std::to_string(s.height) + " (the image), not " +
                                      std::to_string(c->x0) + " " + std::to_string(c->y0) + " " + std::to_string(x1) +
                                      " " + std::to_string(y1));
    }
    return s;
}

SamplingLimits sampling_limits(const RenderOptions& o, std::chrono::steady_clock::time_point start) {
    SamplingLimits limits;
    if (o.time_budget)
        limits.deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(*o.time_budget));
    if (o.noise_threshold) limits.noise_threshold = *o.noise_threshold;
    limits.min_spp = o.min_spp;
    return limits;
}

namespace {

template <class Value>
Value named_value(const char* option, std::optional<Value> parsed, std::string_view name, const char* what,
                  const std::string& expected) {
    if (!parsed)
        throw Error(option, "unknown " + std::string(what) + " '" + std::string(name) + "' (" + expected + ")");
    return *parsed;
}

}  // namespace

IntegratorKind integrator_option(std::string_view name) {
    return named_value("--integrator", parse_integrator(name), name, "integrator", "expected direct or path");
}

TextureFilter texture_filter_option(std::string_view name) {
    return named_value("--texture-filter", parse_texture_filter(name), name, "texture filter",
                       "expected bilinear or mipmap");
}

LightSelection light_selection_option(std::string_view name) {
    return named_value("--light-tree", parse_light_selection(name), name, "light choice", "expected auto, on or off");
}

std::string accel_names() {
    std::string names;
    for (std::string_view n : available_accels()) names += (names.empty() ? "" : ", ") + std::string(n);
    return names;
}

AccelKind accel_option(std::string_view name) {
    return named_value("--accel", parse_accel_kind(name), name, "accelerator", "available: " + accel_names());
}

AovSet aov_option(std::string_view list) {
    std::string bad;
    const std::optional<AovSet> set = parse_aov_list(list, bad);
    if (!set) {
        std::string names;
        for (const AovName& aov : kAovNames) names += std::string(names.empty() ? "" : ", ") + aov.name;
        throw Error("--aov", "unknown AOV '" + bad + "' (expected a comma-separated list of " + names + ")");
    }
    return *set;
}

std::optional<LightSelection> parse_light_selection(std::string_view name) {
    if (name == "auto") return LightSelection::Automatic;
    if (name == "on") return LightSelection::Tree;
    if (name == "off") return LightSelection::Power;
    return std::nullopt;
}

std::string_view light_selection_name(LightSelection selection) {
    switch (selection) {
        case LightSelection::Tree: return "on";
        case LightSelection::Power: return "off";
        case LightSelection::Automatic: break;
    }
    return "auto";
}

}  // namespace sombra
