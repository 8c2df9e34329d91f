// The "direct" integrator of spec §4: radiance arriving along a camera ray
// from point lights, with one shadow ray per light, plus emission seen directly.
#pragma once

#include <cstdint>

#include "accel/accel.h"
#include "core/ray.h"
#include "scene/scene.h"

namespace sombra {

// Rays traced by one worker; summed over workers for the statistics.
struct RayCounters {
    std::uint64_t camera_rays = 0;
    std::uint64_t shadow_rays = 0;
    std::uint64_t nonfinite_samples = 0;  // samples whose radiance was NaN/Inf, dropped (counted as 0)

    RayCounters& operator+=(const RayCounters& b) {
        camera_rays += b.camera_rays;
        shadow_rays += b.shadow_rays;
        nonfinite_samples += b.nonfinite_samples;
        return *this;
    }
};

// Linear RGB radiance L arriving at the ray's origin along -ray.dir
// (ray.dir need not be unit length). `scene.geometry` must be the mesh
// `accel` was built over. Never returns NaN or Inf: a non-finite result is
// counted in counters.nonfinite_samples and returned as 0.
Vec3 trace_direct(const Scene& scene, const Accel& accel, const Ray& ray, RayCounters& counters);

// Where a ray leaving surface point x should start so that it cannot hit the
// surface it leaves: x moved along the geometric normal n_g (pointing to the
// side the ray leaves towards) by a bound on x's floating-point error.
// `error` is that bound per axis (see trace_direct).
inline Vec3 offset_ray_origin(Vec3 x, Vec3 error, Vec3 n_g) {
    const float d = dot(abs(n_g), error);
    return x + d * n_g;
}

}  // namespace sombra
