// Surface materials of spec §5 and §11, as plain data. The BSDFs that
// evaluate and sample them live in render/bsdf.h (render/brdf.h holds the
// version-1 BRDF terms that the direct integrator evaluates).
#pragma once

#include <string>

#include "core/vec3.h"

namespace sombra {

enum class MaterialType {
    Diffuse,     // Lambert, kd / π (§5)
    Phong,       // energy-normalised modified Phong (§5)
    Mirror,      // perfect specular reflection, reflectance kr (§11)
    Dielectric,  // smooth glass: Fresnel reflection and refraction, ior, kt (§11)
    Conductor,   // GGX microfacet metal, Schlick Fresnel from ks, roughness (§11)
    Pbr,         // glTF 2.0 metallic–roughness: base_color, metallic, roughness, ior (§11)
};

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Vec3 kd{0.8f};        // diffuse albedo, each channel in [0, 1]
    Vec3 ks{0.0f};        // Phong specular albedo; Conductor: reflectance at normal incidence
    float shininess = 1;  // Phong exponent n >= 0 (Phong only)
    Vec3 ke{0.0f};        // emitted radiance (two-sided unless emits_front_only)
    Vec3 kr{1.0f};        // Mirror reflectance, each channel in [0, 1]
    Vec3 kt{1.0f};        // Dielectric transmission tint, each channel in [0, 1]
    float ior = 1.5f;     // Dielectric index of refraction inside, > 1 (outside is 1)
    float roughness = 0;  // Conductor roughness r in [0, 1]; GGX α = r²
    Vec3 base_color{1.0f};
    float metallic = 0.0f;
    // Quad lights (§10) emit only toward the side their winding normal
    // (v1 − v0) × (v2 − v0) points to, and are black from behind.
    bool emits_front_only = false;
};

// True when a Phong material can reflect more light than it receives: kd + ks
// exceeds 1 in some channel (spec §5 asks for a warning, from scenes and MTL alike).
inline bool breaks_energy_conservation(const Material& m) {
    return m.type == MaterialType::Phong && max_component(m.kd + m.ks) > 1;
}

// True when the material emits light (some ke component > 0).
inline bool is_emissive(const Material& m) { return max_component(m.ke) > 0.0f; }

// What a face with no material gets (spec §5): diffuse, kd = 0.8 grey.
inline Material default_material() { return Material{"default", MaterialType::Diffuse, Vec3{0.8f}, {}, 1, {}}; }

}  // namespace sombra
