// What a camera ray's first surface hit is, for the render outputs of spec
// §18 (AOVs): the material's albedo after textures, the shading normal
// facing the camera, the distance along the ray and the position. The
// integrators fill it through a recorder hook (FirstHitRecorder) as they
// shade, so asking for AOVs traces no extra ray.
#pragma once

#include "core/ray.h"
#include "render/interaction.h"
#include "render/sample_recorder.h"
#include "scene/material.h"

namespace sombra {

struct FirstHit {
    bool hit = false;  // false: the camera ray left the scene, the rest is zero
    Vec3 albedo{0.0f};
    Vec3 normal{0.0f};  // world-space n_s, turned to face the ray's origin
    float depth = 0;    // distance from the ray's origin to the hit
    Vec3 position{0.0f};
};

// The albedo §18 names for each material, read from the material resolved
// at the hit (textures applied): what a denoiser takes as the surface's colour.
inline Vec3 material_albedo(const Material& m) {
    switch (m.type) {
        case MaterialType::Diffuse: return m.kd;
        case MaterialType::Phong: return m.kd + m.ks;
        case MaterialType::Mirror: return m.kr;
        case MaterialType::Dielectric: return m.kt;
        case MaterialType::Conductor: return m.ks;
        case MaterialType::Pbr: return m.base_color;
        case MaterialType::Interface: return Vec3{0.0f};
    }
    return m.kd;
}

// Records the first surface the camera ray reaches into a FirstHit and
// nothing else: every other hook is NoRecorder's empty one.
class FirstHitRecorder : public NoRecorder {
public:
    // The first surface "media notwithstanding" (spec §25): also where the
    // camera ray scatters in a medium before it.
    static constexpr bool kWantsFirstSurface = true;
    explicit FirstHitRecorder(FirstHit& out) : out_(out) {}

    void surface(const Ray& ray, const Hit& hit, const SurfaceInteraction& si, const Material& material, Vec3) {
        if (out_.hit) return;  // a later vertex of the path
        out_.hit = true;
        out_.albedo = material_albedo(material);
        out_.normal = dot(si.n_s, ray.dir) > 0.0f ? -si.n_s : si.n_s;
        out_.depth = hit.t * length(ray.dir);
        out_.position = si.position;
    }

private:
    FirstHit& out_;
};

}  // namespace sombra
