// A directional light (spec §16): irradiance E from infinitely far, arriving
// along `direction` everywhere, with no falloff.
#pragma once

#include <limits>

#include "render/lights/delta_arrival.h"
#include "scene/light.h"

namespace sombra {

// Explain's name for what arrives: E.
inline constexpr const char* kDirectionalLightIncident = "E";

inline DeltaArrival directional_light_arrival(const PunctualLight& light, Vec3 /*x*/) {
    return {-light.direction, std::numeric_limits<float>::infinity()};
}

// The same I (or E) in every direction it shines.
inline float directional_light_factor(const PunctualLight& /*light*/, Vec3 /*wi*/) { return 1.0f; }

}  // namespace sombra
