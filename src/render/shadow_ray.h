// Shadow rays through media and interface surfaces (spec §26): how much of
// a light's radiance reaches a point, rather than only whether it does.
#pragma once

#include <cstdint>

#include "accel/accel.h"
#include "core/ray.h"
#include "render/media/grid_medium.h"
#include "render/media/medium_boundary.h"
#include "scene/scene.h"

namespace sombra {

// The share of light carried along `shadow` (spec §10's shadow ray) that
// arrives: 0 where a surface blocks it; else, with `media` on, the
// transmittance of the media it passes through, starting in `medium` and
// changing where it crosses an "interface" surface, which never blocks.
// With `media` off (the direct integrator) interfaces are crossed and media
// ignored. The transmittance is exact for homogeneous media, and ratio
// tracked with numbers from `rng` through grid media.
Vec3 shadow_transmittance(const Accel& accel, const Scene& scene, const Ray& shadow, std::uint32_t medium, bool media,
                          TrackingRng* rng);

// intersect() for a ray that crosses "interface" surfaces unchanged (the
// direct integrator's camera rays, which ignore media): the first other
// hit, its t measured along `ray` as given.
bool intersect_past_interfaces(const Accel& accel, const Scene& scene, const Ray& ray, Hit& hit);

// What shadow rays leaving a surface pass through: the media on its two
// sides, or (media off) none but interfaces to cross.
struct ShadowMedia {
    const Scene* scene = nullptr;
    MediumSides sides;
    bool media = true;
    TrackingRng* rng = nullptr;  // for grid media
};

// shadow_transmittance for a shadow ray leaving a surface of geometric
// normal n_g (facing the side sides.near is on).
inline Vec3 shadow_transmittance(const Accel& accel, const ShadowMedia& m, Vec3 n_g, const Ray& shadow) {
    return shadow_transmittance(accel, *m.scene, shadow, medium_toward(m.sides, n_g, shadow.dir), m.media, m.rng);
}

}  // namespace sombra
