// Scene JSON (spec §2, §3, §5, §8) → loaded Scene in world space.
#pragma once

#include <filesystem>
#include <string>

#include "core/error.h"
#include "scene/scene.h"

namespace sombra {

// Reads and validates a scene file, loads every object's mesh (paths relative
// to the scene's folder), applies transforms and material overrides, and
// concatenates all objects into Scene::geometry. Throws Error with WHERE as
// "scene.json:line:col" for malformed JSON and "scene.json: /json/path" (the
// JSON pointer of the offending value) for semantic errors.
Scene load_scene_file(const std::filesystem::path& path, Diagnostics& diag);

// The same from JSON text already in memory; `path` names it in messages and
// anchors relative mesh paths.
Scene load_scene_text(const std::string& text, const std::filesystem::path& path, Diagnostics& diag);

}  // namespace sombra
