// The scene a Python `sombra.Scene` holds: a loaded scene with its render
// settings, and what renders share of it.
#pragma once

#include <shared_mutex>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "io/loaded_scene.h"

namespace sombra::python {

struct PyScene {
    LoadedScene loaded;
    std::string source;                 // the file it came from, as explain names it
    std::vector<std::string> warnings;  // the reader's, "WHERE: WHAT"
    // Renders read the scene together; building its mip pyramids (the first
    // render under texture_filter="mipmap") writes it, alone.
    std::shared_mutex access;
    bool mip_pyramids_built = false;
};

// The settings as the dict `Scene.render_settings` shows.
pybind11::dict settings_dict(const RenderSettings& settings);

}  // namespace sombra::python
