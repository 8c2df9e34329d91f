// The delta light types side by side: the one place that chooses a type's
// arrival and factor (render/lights/delta_arrival.h) and explain's name for
// what arrives. A new type is its own file beside point_light.h, a case in
// each switch here, and its row in scene/light.h.
#pragma once

#include "render/lights/delta_arrival.h"
#include "render/lights/directional_light.h"
#include "render/lights/point_light.h"
#include "render/lights/spot_light.h"
#include "scene/light.h"

namespace sombra {

inline DeltaArrival delta_arrival(const PunctualLight& light, Vec3 x) {
    switch (light.type) {
        case LightType::Spot: return spot_light_arrival(light, x);
        case LightType::Directional: return directional_light_arrival(light, x);
        case LightType::Point: break;
    }
    return point_light_arrival(light, x);
}

// The light's own factor towards a point it reaches along ω_i = `wi`.
inline float delta_factor(const PunctualLight& light, Vec3 wi) {
    switch (light.type) {
        case LightType::Spot: return spot_light_factor(light, wi);
        case LightType::Directional: return directional_light_factor(light, wi);
        case LightType::Point: break;
    }
    return point_light_factor(light, wi);
}

// What explain calls the arriving factor of a light of `type`.
constexpr const char* delta_incident_symbol(LightType type) {
    switch (type) {
        case LightType::Spot: return kSpotLightIncident;
        case LightType::Directional: return kDirectionalLightIncident;
        case LightType::Point: break;
    }
    return kPointLightIncident;
}

}  // namespace sombra
