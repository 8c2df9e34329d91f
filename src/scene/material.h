// Surface materials of spec §5, as plain data. The BRDFs that evaluate them
// live in render/brdf.h.
#pragma once

#include <string>

#include "core/vec3.h"

namespace sombra {

enum class MaterialType { Diffuse, Phong };

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Vec3 kd{0.8f};        // diffuse albedo, each channel in [0, 1]
    Vec3 ks{0.0f};        // Phong specular albedo (Phong only)
    float shininess = 1;  // Phong exponent n >= 0 (Phong only)
    Vec3 ke{0.0f};        // emitted radiance, seen directly by camera rays
};

// True when a Phong material can reflect more light than it receives: kd + ks
// exceeds 1 in some channel (spec §5 asks for a warning, from scenes and MTL alike).
inline bool breaks_energy_conservation(const Material& m) {
    return m.type == MaterialType::Phong && max_component(m.kd + m.ks) > 1;
}

// What a face with no material gets (spec §5): diffuse, kd = 0.8 grey.
inline Material default_material() { return Material{"default", MaterialType::Diffuse, Vec3{0.8f}, {}, 1, {}}; }

}  // namespace sombra
