// The integrators: radiance arriving at a camera ray's origin. `direct`
// (spec §4, direct_integrator.cpp) adds the delta lights' direct light
// (point, spot, directional: render/delta_lights.h) to what the camera sees; `path`
// (spec §10) estimates the whole rendering equation by unidirectional path
// tracing with next-event estimation and multiple importance sampling. Both
// read the same lights (render/lights/lights.h) and BSDFs (render/bsdf/bsdf.h).
#pragma once

#include <cstdint>

#include "accel/accel.h"
#include "core/ray.h"
#include "render/lights/lights.h"
#include "render/ray_counters.h"
#include "render/sample_record.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace sombra {

struct FirstHit;  // render/first_hit.h

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
    int max_volume_depth = 256;  // path: the most scattering events in media on a path (spec §26)
    // Mip-mapping (--texture-filter mipmap): the rays given to trace_direct
    // and trace_path are camera rays of a camera whose pixel is
    // camera_pixel_area (render/ray_cone.h), and their cones choose the
    // textures' levels. False: every lookup at full resolution.
    bool ray_cones = false;
    Vec3 camera_pixel_area{0.0f};
    bool orthographic_camera = false;  // the cones are the pixel's width, not spreading
};

// Linear RGB radiance arriving at the ray's origin along -ray.dir (ray.dir
// need not be unit length), by spec §4: background, or emission plus each
// visible delta light's term (I/|c−x|² · f · |n_s·ω_i| for a point light). Never returns NaN or Inf:
// a non-finite result is counted in counters.nonfinite_samples and returned as 0.
Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters);
// The same, compiled from the same code, writing every term into `record`
// (`sombra explain`); returns exactly what the function above returns.
Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters, SampleRecord& record);
// The same, also writing the ray's first hit into `first` (the AOVs, spec
// §18); returns exactly what the first function returns.
Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters, FirstHit& first);

// The path integrator's estimate of the same radiance (spec §10), drawing
// its random numbers from `samples`. Never NaN or Inf (as trace_direct).
Vec3 trace_path(const IntegratorContext& ctx, const Ray& ray, SampleStream& samples, RayCounters& counters);
// The same, writing every vertex into `record`; returns exactly what the function above returns.
Vec3 trace_path(const IntegratorContext& ctx, const Ray& ray, SampleStream& samples, RayCounters& counters,
                SampleRecord& record);
// The same, also writing the camera ray's first hit into `first`.
Vec3 trace_path(const IntegratorContext& ctx, const Ray& ray, SampleStream& samples, RayCounters& counters,
                FirstHit& first);

}  // namespace sombra
