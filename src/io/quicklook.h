// The quick look of spec §7: a scene made on the fly for a lone model file
// (.obj, .ply, .gltf, .glb), so that `sombra render model.obj` shows it.
#pragma once

#include <filesystem>

#include "core/error.h"
#include "io/loaded_scene.h"

namespace sombra {

// Loads the model and frames it: a look-at camera with a 40° vertical field
// of view, in a three-quarter view from the model's front (+z), left and
// above, at the distance where the bounding sphere fits the frame; a key, a fill and a rim light
// scaled to the model's size so the lit side shows mid-grey to light tones;
// the model's own MTL materials, or neutral grey. Assumes +y is up. A glTF
// file's first camera, perspective (its aspect ratio sets the default
// image's height) or orthographic (spec §24: ymag and the image's aspect),
// replaces the framing, and its point lights, when it has any, replace the
// three lights (spec §7, §13).
LoadedScene make_quicklook_scene(const std::filesystem::path& model, Diagnostics& diag);

}  // namespace sombra
