// Scenes for the renderer: a scene JSON file (spec §2, §3, §5, §8) loaded
// into world space, or the quick look of spec §7, a scene made on the fly
// for a lone model file.
#pragma once

#include <filesystem>
#include <string>

#include "core/error.h"
#include "io/loaded_scene.h"

namespace sombra {

// Reads and validates a scene file, loads every object's mesh (paths relative
// to the scene's folder), applies transforms and material overrides, and
// concatenates all objects into Scene::geometry. Throws Error with WHERE as
// "scene.json:line:col" for malformed JSON and "scene.json: /json/path" (the
// JSON pointer of the offending value) for semantic errors. The settings are
// the file's "render" section, checked against render_settings_problem.
LoadedScene load_scene_file(const std::filesystem::path& path, Diagnostics& diag);

// The same from JSON text already in memory; `path` names it in messages and
// anchors relative mesh paths.
LoadedScene load_scene_text(const std::string& text, const std::filesystem::path& path, Diagnostics& diag);

// Loads the model and frames it: a look-at camera with a 40° vertical field
// of view, in front of the model (+z) and a little above, at the distance
// where the bounding sphere fits the frame; a key, a fill and a rim light
// scaled to the model's size so the lit side shows mid-grey to light tones;
// the model's own MTL materials, or neutral grey. Assumes +y is up. A glTF
// file's first perspective camera replaces the framing (its aspect ratio
// sets the default image's height), and its point lights, when it has any,
// replace the three lights (spec §7, §13).
LoadedScene make_quicklook_scene(const std::filesystem::path& model, Diagnostics& diag);

}  // namespace sombra
