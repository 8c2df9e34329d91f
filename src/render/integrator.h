// The integrators: radiance arriving at a camera ray's origin. `direct`
// (spec §4) adds point lights' direct light to what the camera sees; `path`
// (spec §10) estimates the whole rendering equation by unidirectional path
// tracing with next-event estimation and multiple importance sampling. Both
// read the same lights (render/lights.h) and BSDFs (render/bsdf.h).
#pragma once

#include <cstdint>

#include "accel/accel.h"
#include "core/ray.h"
#include "render/lights.h"
#include "render/sample_record.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace sombra {

// Rays traced by one worker; summed over workers for the statistics.
struct RayCounters {
    std::uint64_t camera_rays = 0;
    std::uint64_t shadow_rays = 0;        // every next-event (shadow) ray
    std::uint64_t bounce_rays = 0;        // rays traced by BSDF sampling (path integrator)
    std::uint64_t nonfinite_samples = 0;  // samples whose radiance was NaN/Inf, dropped (counted as 0)

    std::uint64_t rays() const { return camera_rays + shadow_rays + bounce_rays; }
    RayCounters& operator+=(const RayCounters& b) {
        camera_rays += b.camera_rays;
        shadow_rays += b.shadow_rays;
        bounce_rays += b.bounce_rays;
        nonfinite_samples += b.nonfinite_samples;
        return *this;
    }
};

// How the path integrator reaches emitters and the environment. Renders
// always use Mis; the single strategies exist so that tests can check that
// all three estimate the same value (each is unbiased on its own).
enum class LightStrategy {
    Mis,        // next-event estimation and BSDF sampling, power heuristic
    LightOnly,  // next-event estimation only (emitters hit by a bounce count 0)
    BsdfOnly,   // BSDF sampling only (no next-event estimation for them)
};

// What an integrator reads; all of it shared, read-only, by every thread.
struct IntegratorContext {
    const Scene* scene = nullptr;  // scene->geometry is the mesh `accel` was built over
    const Accel* accel = nullptr;
    const LightSet* lights = nullptr;
    int max_depth = 8;  // path: the most scattering events on a path (spec §10)
    LightStrategy strategy = LightStrategy::Mis;
    // Mip-mapping (--texture-filter mipmap): the rays given to trace_direct
    // and trace_path are camera rays of a camera whose pixel is
    // camera_pixel_area (render/ray_cone.h), and their cones choose the
    // textures' levels. False: every lookup at full resolution.
    bool ray_cones = false;
    Vec3 camera_pixel_area{0.0f};
};

// Linear RGB radiance arriving at the ray's origin along -ray.dir (ray.dir
// need not be unit length), by spec §4: background, or emission plus each
// visible point light's I/|c−x|² · f · |n_s·ω_i|. Never returns NaN or Inf:
// a non-finite result is counted in counters.nonfinite_samples and returned as 0.
Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters);
// The same, compiled from the same code, writing every term into `record`
// (`sombra explain`); returns exactly what the function above returns.
Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters, SampleRecord& record);

// The path integrator's estimate of the same radiance (spec §10), drawing
// its random numbers from `samples`. Never NaN or Inf (as trace_direct).
Vec3 trace_path(const IntegratorContext& ctx, const Ray& ray, SampleStream& samples, RayCounters& counters);
// The same, writing every vertex into `record`; returns exactly what the function above returns.
Vec3 trace_path(const IntegratorContext& ctx, const Ray& ray, SampleStream& samples, RayCounters& counters,
                SampleRecord& record);

}  // namespace sombra
