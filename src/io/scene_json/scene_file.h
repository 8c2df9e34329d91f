// Scene files (spec §2, §3, §5, §8): the JSON read and checked, every
// object's mesh file loaded and placed in world space by the scene's builder
// (scene/scene_builder.h), the "render" section read beside the scene.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>

#include "core/error.h"
#include "io/loaded_scene.h"
#include "io/mesh_file.h"

namespace sombra {

// Reads and validates a scene file, loads every object's mesh (paths relative
// to the scene's folder), and adds them to a SceneBuilder with their
// transforms and material overrides. Throws Error with WHERE as
// "scene.json:line:col" for malformed JSON and "scene.json: /json/path" (the
// JSON pointer of the offending value) for semantic errors. The settings are
// the file's "render" section, checked against render_settings_problem.
LoadedScene load_scene_file(const std::filesystem::path& path, Diagnostics& diag);

// The mesh files a scene has read, by canonical path: a Python scene that
// is edited and assembled again reads none of them twice.
struct MeshFileCache {
    std::map<std::filesystem::path, std::shared_ptr<const LoadedMesh>> meshes;
};

// The same from JSON text already in memory; `path` names it in messages and
// anchors relative mesh paths. With `given_meshes` (meshes made from arrays,
// io/array_mesh.h: the Python module's scenes from code), an object may name
// one by index, {"mesh": i, "material": …, "transform": …}, in place of a
// "file"; without, "mesh" is an unknown key as in any scene file. With
// `cache`, a mesh file is taken from it when there, else read and kept in it.
LoadedScene load_scene_text(const std::string& text, const std::filesystem::path& path, Diagnostics& diag,
                            std::span<const LoadedMesh* const> given_meshes = {}, MeshFileCache* cache = nullptr);

// A scene file's text, as load_scene_file reads it (its size checked first).
std::string read_scene_text(const std::filesystem::path& path);

}  // namespace sombra
