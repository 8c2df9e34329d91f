// What `render` and `explain` do alike before rendering: read the input,
// apply the command line's overrides, and say what is off.
#pragma once

#include <filesystem>
#include <string>

#include "app/cli.h"
#include "render/lights.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace sombra {

// Each message stays one line whatever the paths in it hold: control
// characters (a newline or NUL in a file name) are shown as '?'.
std::string one_line(std::string text);

// A scene .json, or a model for the quick look (spec §7). Throws Error.
Scene load_input(const std::filesystem::path& input, Diagnostics& diag);

// The scene's render settings with the command line's overrides applied,
// each checked against the same limits as the scene file's values (a problem
// names the option that caused it). Throws Error.
RenderSettings resolve_settings(const RenderSettings& scene_settings, const CliOptions& options);

// The light choice --light-tree asks for.
LightSelection light_selection(const CliOptions& options);

// Prints the loader's warnings, and the one about the direct integrator
// meeting version-2 content (spec §10), to stderr.
void print_warnings(const Diagnostics& diag, const Scene& scene, const RenderSettings& settings, const CliOptions& options);

}  // namespace sombra
