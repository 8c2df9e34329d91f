// A spot light (spec §16): a point light inside a cone about `direction`,
// its I scaled by the falloff s² (scene/light.h's spot_falloff) at the
// direction the light leaves in; nothing outside the cone.
#pragma once

#include "render/lights/delta_arrival.h"
#include "scene/light.h"

namespace sombra {

// Explain's name for what arrives: I·s²/|c − x|².
inline constexpr const char* kSpotLightIncident = "I·s²/|c−x|²";

inline DeltaArrival spot_light_arrival(const PunctualLight& light, Vec3 x) {
    return arrival_from_position(light.position, x);
}

// s² at the direction the light leaves in, −ω_i; 0 outside the cone.
inline float spot_light_factor(const PunctualLight& light, Vec3 wi) {
    return spot_falloff(light, -dot(light.direction, wi));
}

}  // namespace sombra
