// The denoiser's layers (spec §25) between Python and C++: as the dict
// entries `render(..., aov=["denoise"])` returns, and back from such a dict
// for `sombra.denoise`.
#pragma once

#include <pybind11/pybind11.h>

#include "denoise/denoise_layers.h"

namespace sombra::python {

// Adds each layer the denoiser reads to `out`, keyed by its EXR layer name
// without the channel ("variance", "denoise.A", …, "denoise.depthB"): numpy
// float32 arrays (height, width, 3), or (height, width) for the depths.
// The layers' values are moved out.
void add_denoise_layers(pybind11::dict& out, DenoiseLayers&& layers);

}  // namespace sombra::python
