// Point lights (spec §4): what scene files list and what model files (glTF's
// KHR_lights_punctual) may bring along.
#pragma once

#include "core/vec3.h"

namespace sombra {

struct PointLight {
    Vec3 position;
    Vec3 intensity;  // radiant intensity, RGB (W/sr)
};

}  // namespace sombra
