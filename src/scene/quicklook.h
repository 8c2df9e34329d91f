// The quick look of spec §7: a scene made on the fly for a lone model file.
#pragma once

#include <filesystem>

#include "core/error.h"
#include "scene/scene.h"

namespace sombra {

// Loads the model and frames it: a look-at camera with a 40° vertical field
// of view, in front of the model (+z) and a little above, at the distance
// where the bounding sphere fits the frame; a key, a fill and a rim light
// scaled to the model's size so the lit side shows mid-grey to light tones;
// the model's own MTL materials, or neutral grey. Assumes +y is up.
Scene make_quicklook_scene(const std::filesystem::path& model, Diagnostics& diag);

}  // namespace sombra
