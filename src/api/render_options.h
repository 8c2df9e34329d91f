// What a front end asks of a render, as typed values (spec §1, §10, §18):
// the overrides of the scene's "render" section and how to run it. The
// command line parses its words into these, Python converts its keyword
// arguments, the viewer fills them from its own settings; all are checked
// here alike, and a problem names the option as the command line spells it.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "accel/accel.h"
#include "render/aov_set.h"
#include "render/lights/lights.h"
#include "render/render.h"
#include "render/render_settings.h"

namespace sombra {

// Values that replace the scene's own "render" settings; unset = as the scene says.
struct SettingOverrides {
    std::optional<int> width, height, spp;
    std::optional<std::uint64_t> seed;
    std::optional<IntegratorKind> integrator;
    std::optional<int> max_depth;
    std::optional<int> max_volume_depth;
    std::optional<TextureFilter> texture_filter;
};

struct RenderOptions {
    SettingOverrides overrides;
    int threads = 0;  // 0 = all hardware threads
    AccelKind accel = AccelKind::Bvh;
    LightSelection light_selection = LightSelection::Automatic;
    std::optional<std::int64_t> frame;  // spec §22: the moment frame / fps; unset = the first frame
    std::optional<double> time_budget;  // spec §18: seconds from the start of the command or call
    std::optional<double> noise_threshold;
    int min_spp = 16;
    // Spec §27: render only this window of the image (its pixels exactly as
    // in the whole render) and output an image of its size; unset = all.
    std::optional<PixelWindow> crop;
    AovSet aovs;
    bool denoise = false;  // spec §25: the image denoised once the last pass is done
};

// Limits on the options beside those of RenderSettings (render_settings.h).
inline constexpr int kMaxThreads = 4096;           // more workers is a typo, not a machine
inline constexpr double kMaxTimeBudget = 1e7;      // 116 days; more would overflow the clock's deadline
inline constexpr double kMaxNoiseThreshold = 1e6;  // a relative error; far above any useful one
inline constexpr std::int64_t kMaxFrame = (std::int64_t{1} << 31) - 1;  // spec §27: 0 ≤ F ≤ 2³¹ − 1

// Throws Error(option, what) for a value outside its range, the option named
// as the command line spells it ("--threads"); width, height and spp are
// checked by resolve_settings, whose limit on pixels depends on both sides.
void check_render_options(const RenderOptions& options);

// The scene's settings with `overrides` applied, each checked against the
// limits the scene file's values obey (render_settings_problem). Throws
// Error naming the option ("--width") that caused a problem.
RenderSettings resolve_settings(const RenderSettings& scene_settings, const SettingOverrides& overrides);

// The settings a render runs at: resolve_settings, and under a time budget
// without an spp override no spp limit, since the budget decides (spec §18).
// Throws UsageError("--denoise", ...) when options.denoise meets fewer than
// 2 samples per pixel: the denoiser compares each pixel's two halves, and
// Error("--crop", ...) for a window outside the image.
RenderSettings resolve_render_settings(const RenderSettings& scene_settings, const RenderOptions& options);

// When pixels stop sampling, as the time budget, noise threshold and
// min_spp ask; the budget counts from `start` (the wait the user asked for).
SamplingLimits sampling_limits(const RenderOptions& options, std::chrono::steady_clock::time_point start);

// The named options' values as every front end reads them; each throws
// Error(option, "unknown integrator 'x' (expected direct or path)") and the like.
IntegratorKind integrator_option(std::string_view name);
TextureFilter texture_filter_option(std::string_view name);
LightSelection light_selection_option(std::string_view name);
AccelKind accel_option(std::string_view name);
AovSet aov_option(std::string_view list);  // "albedo,depth"

// The accelerators this build has, as --accel names them: "bvh, brute, embree".
std::string accel_names();

// --light-tree's names: "auto", "on" (the tree), "off" (by power).
std::optional<LightSelection> parse_light_selection(std::string_view name);
std::string_view light_selection_name(LightSelection selection);

}  // namespace sombra
