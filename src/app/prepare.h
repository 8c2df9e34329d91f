// What `render` and `explain` do alike before rendering: read the input,
// apply the command line's overrides, and say what is off.
#pragma once

#include <chrono>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>

#include "app/cli.h"
#include "core/error.h"
#include "io/loaded_scene.h"
#include "render/lights.h"
#include "render/render.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace sombra {

// Each message stays one line whatever the paths in it hold: control
// characters (a newline or NUL in a file name) are shown as '?'.
std::string one_line(std::string text);

// The path's extension in lower case (".json", ".glb"), "" when it has none.
std::string lower_extension(const std::filesystem::path& path);

// Checks, before any work, that a side file (statistics, explain's SVG) can
// be written: its folder exists and the path is not a folder. Throws Error.
void check_side_file_path(const std::filesystem::path& path);

// A scene .json, or a model for the quick look (spec §7). Throws Error.
LoadedScene load_input(const std::filesystem::path& input, Diagnostics& diag);

// The input's render settings with the command line's overrides applied,
// each checked against the same limits as the scene file's values (a problem
// names the option that caused it). Throws Error.
RenderSettings resolve_settings(const RenderSettings& scene_settings, const CliOptions& options);

// The settings `sombra render` renders at: resolve_settings, and under a
// time budget without --spp no spp limit, since the budget decides (spec §18).
RenderSettings resolve_render_settings(const RenderSettings& scene_settings, const CliOptions& options);

// When pixels stop sampling, as --time, --noise-threshold and --min-spp ask;
// the budget counts from `start`, the command's start (the wait the user asked for).
SamplingLimits sampling_limits(const CliOptions& options, std::chrono::steady_clock::time_point start);

// `sombra explain`'s pixel and sample checked against the image `settings`
// describe. Throws Error naming the pixel or --sample.
void check_explain_pixel(const CliOptions& options, const RenderSettings& settings);

// What the textures need for `settings`: their mip pyramids under
// TextureFilter::Mipmap (scene/texture_mipmap.h), nothing otherwise.
void prepare_textures(Scene& scene, const RenderSettings& settings);

// The moment of `frame` in seconds: frame / fps (24 without an "animation").
double frame_time(const Scene& scene, std::int64_t frame);

// Moves an animated scene to --frame's moment, or its first frame's
// (spec §22); a scene without animation is left as it is. Throws Error.
void move_to_frame(Scene& scene, const CliOptions& options);

// The light choice --light-tree asks for.
LightSelection light_selection(const CliOptions& options);

// Prints the loader's warnings, and the one about the direct integrator
// meeting version-2 content (spec §10), to stderr.
void print_warnings(const Diagnostics& diag, const Scene& scene, const RenderSettings& settings,
                    const CliOptions& options);

// Runs `body` (returning the exit status) and turns what it throws into the
// one line of spec §1, "sombra: error: WHERE: WHAT", and exit status 1.
template <class Body>
int reporting_errors(const CliOptions& o, Body&& body) {
    try {
        return body();
    } catch (const Error& e) {
        std::cerr << "sombra: error: " << one_line(e.where() + ": " + e.message()) << '\n';
    } catch (const std::bad_alloc&) {
        std::cerr << "sombra: error: " << one_line(o.input) << ": out of memory\n";
    } catch (const std::exception& e) {
        // A bug, not the input's fault; still one line and no image.
        std::cerr << "sombra: error: " << one_line(o.input) << ": internal error: " << one_line(e.what()) << '\n';
    }
    return 1;
}

}  // namespace sombra
