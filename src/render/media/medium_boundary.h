// Which medium a path is in (spec §26): objects with an "interior" bound
// one, the side their winding normals point away from; "interface"
// surfaces are crossed unchanged. A surface of an object without an
// interior keeps the medium the path was in.
#pragma once

#include <cstdint>

#include "core/vec3.h"
#include "render/interaction.h"
#include "scene/scene.h"

namespace sombra {

// True when a path must know which medium it is in: the scene has media or
// interface surfaces. Scenes without either never pay for tracking.
inline bool tracks_media(const Scene& scene) {
    return !scene.media.empty() || scene.interface_material != kNoInterface;
}

// A ray crossing more interface surfaces than this ends (a path) or is taken
// as blocked (a shadow ray): it bounds the work of a ray caught between
// coincident interfaces. Crossings count against no depth (spec §26).
inline constexpr int kMaxInterfaceCrossings = 1024;

// True when `triangle` of surface_mesh(scene, instance) is an "interface".
inline bool is_interface(const Scene& scene, std::uint32_t triangle, std::uint32_t instance) {
    return scene.interface_material != kNoInterface &&
           surface_mesh(scene, instance).material_ids[triangle] == scene.interface_material;
}

// The media on the two sides of a surface hit: `near` on the side the ray
// came from (the side n_g faces), `far` beyond it.
struct MediumSides {
    std::uint32_t near = kNoMedium;
    std::uint32_t far = kNoMedium;
    bool boundary = false;  // the surface's object has an interior
};

// The sides at `si`, reached by a path in medium `current`.
inline MediumSides medium_sides(const Scene& scene, const SurfaceInteraction& si, std::uint32_t current) {
    const SceneObject* object = object_of_surface(scene, si.triangle, si.instance);
    if (object == nullptr || !object->bounds_medium) return {current, current, false};
    const std::uint32_t interior =
        si.instance == kNoInstance ? object->interior : scene.instances[si.instance].interior;
    // `outside`: the ray arrived from the winding normal's side, the exterior.
    return si.outside ? MediumSides{object->exterior, interior, true} : MediumSides{interior, object->exterior, true};
}

// The medium a ray leaving the surface in direction w travels in.
inline std::uint32_t medium_toward(const MediumSides& sides, Vec3 n_g, Vec3 w) {
    return dot(n_g, w) > 0.0f ? sides.near : sides.far;
}

}  // namespace sombra
