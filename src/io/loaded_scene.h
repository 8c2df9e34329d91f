// What the scene readers return (io/scene_json/scene_file.h): the scene model
// and the render settings the input asks for, which the command line may
// then override. The settings are render/'s type; the model knows nothing of them.
#pragma once

#include "render/render_settings.h"
#include "scene/scene.h"

namespace sombra {

struct LoadedScene {
    Scene scene;
    RenderSettings settings;  // the file's "render" section; defaults where it has none
};

}  // namespace sombra
