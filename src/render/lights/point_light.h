// A point light (spec §4): I from `position`, the same in every direction,
// falling off with the square of the distance.
#pragma once

#include "render/lights/delta_arrival.h"
#include "scene/light.h"

namespace sombra {

// Explain's name for what arrives: I/|c − x|².
inline constexpr const char* kPointLightIncident = "I/|c−x|²";

inline DeltaArrival point_light_arrival(const PunctualLight& light, Vec3 x) {
    return arrival_from_position(light.position, x);
}

// The same I (or E) in every direction it shines.
inline float point_light_factor(const PunctualLight& /*light*/, Vec3 /*wi*/) { return 1.0f; }

}  // namespace sombra
