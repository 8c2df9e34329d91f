#include "render/shadow_ray.h"

#include <cmath>

#include "render/interaction.h"
#include "render/media/homogeneous_medium.h"
#include "render/media/medium_boundary.h"

namespace sombra {

namespace {

// The transmittance of `medium` from `origin` along the unit direction `dir`
// over `distance` (vacuum: 1).
Vec3 segment_transmittance(const Scene& scene, std::uint32_t medium, Vec3 origin, Vec3 dir, float distance,
                           TrackingRng* rng) {
    if (medium == kNoMedium) return Vec3{1.0f};
    const Medium& m = scene.media[medium];
    return m.density ? grid_transmittance(m, origin, dir, distance, *rng) : homogeneous_transmittance(m, distance);
}

}  // namespace

Vec3 shadow_transmittance(const Accel& accel, const Scene& scene, const Ray& shadow, std::uint32_t medium, bool media,
                          TrackingRng* rng) {
    if (!media) medium = kNoMedium;
    const float dir_length = length(shadow.dir);
    const Vec3 dir = shadow.dir / dir_length;
    if (scene.interface_material == kNoInterface) {
        if (occluded(accel, shadow)) return Vec3{0.0f};
        return medium == kNoMedium
                   ? Vec3{1.0f}
                   : segment_transmittance(scene, medium, shadow.origin, dir, shadow.tmax * dir_length, rng);
    }
    Ray ray = shadow;
    Vec3 transmittance{1.0f};
    for (int crossings = 0; crossings < kMaxInterfaceCrossings; ++crossings) {
        Hit hit;
        if (!intersect(accel, ray, hit))
            return transmittance * segment_transmittance(scene, medium, ray.origin, dir, ray.tmax * dir_length, rng);
        if (!is_interface(scene, hit.triangle, hit.instance)) return Vec3{0.0f};
        transmittance = transmittance * segment_transmittance(scene, medium, ray.origin, dir, hit.t * dir_length, rng);
        if (!(max_component(transmittance) > 0.0f)) return Vec3{0.0f};
        const SurfaceInteraction si = make_surface_interaction(scene, ray, hit);
        if (media) medium = medium_sides(scene, si, medium).far;
        ray = Ray{offset_ray_origin(si.position, si.position_error, -si.n_g), ray.dir, ray.tmax - hit.t};
    }
    return Vec3{0.0f};
}

bool intersect_past_interfaces(const Accel& accel, const Scene& scene, const Ray& ray, Hit& hit) {
    if (!intersect(accel, ray, hit)) return false;
    if (scene.interface_material == kNoInterface) return true;
    Ray rest = ray;
    float travelled = 0.0f;
    for (int crossings = 0; is_interface(scene, hit.triangle, hit.instance); ++crossings) {
        if (crossings == kMaxInterfaceCrossings) return false;
        const SurfaceInteraction si = make_surface_interaction(scene, rest, hit);
        travelled += hit.t;
        rest = Ray{offset_ray_origin(si.position, si.position_error, -si.n_g), rest.dir, rest.tmax - hit.t};
        if (!intersect(accel, rest, hit)) return false;
    }
    hit.t += travelled;
    return true;
}

}  // namespace sombra
