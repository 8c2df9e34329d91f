// Where every front end's scene comes from: a scene file, or a model for
// the quick look (spec §7), chosen by the file's extension.
#pragma once

#include <filesystem>
#include <string>

#include "core/error.h"
#include "io/loaded_scene.h"

namespace sombra {

// The path's extension in lower case (".json", ".glb"), "" when it has none.
std::string lower_extension(const std::filesystem::path& path);

// A scene .json, or a model (.obj, .ply, .gltf, .glb) for the quick look.
// Throws Error; warnings go to `diag`.
LoadedScene load_input(const std::filesystem::path& input, Diagnostics& diag);

}  // namespace sombra
