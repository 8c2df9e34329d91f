// The render loop: every pixel's samples through the integrator onto the
// film, in parallel tiles.
#pragma once

#include <atomic>
#include <cstdint>

#include "accel/accel.h"
#include "render/camera.h"
#include "render/film.h"
#include "render/integrator.h"
#include "render/lights.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace sombra {

// Shared with whoever watches the render (the progress bar): the loop adds
// to the counts after each tile and stops early once `cancel` is set.
struct RenderProgress {
    std::atomic<std::uint64_t> samples_done{0};  // pixel samples finished so far (of width · height · spp)
    std::atomic<std::uint64_t> rays_traced{0};   // camera, shadow and bounce rays so far
    std::atomic<bool> cancel{false};
};

struct RenderJob {
    const Scene* scene = nullptr;  // geometry must be the mesh `accel` was built over
    const Accel* accel = nullptr;
    Camera camera;
    LightSet lights;          // the scene's lights as the integrator samples them
    RenderSettings settings;  // image size, spp, seed, integrator and depth actually used
    int threads = 0;          // worker threads; 0 = all hardware threads
};

// The job for rendering `scene` with `accel` at `settings`, with the scene's
// camera resolved for that image size and its lights gathered for the
// integrator (under `path` the background is a constant environment light),
// emitters chosen as `light_selection` says (render/lights.h).
RenderJob make_render_job(const Scene& scene, const Accel& accel, const RenderSettings& settings, int threads = 0,
                          LightSelection light_selection = LightSelection::Automatic);

// What the integrators read for `job`.
IntegratorContext make_integrator_context(const RenderJob& job);

// Sample k (0 … spp − 1) of pixel (i, j), exactly as render_image computes
// it (the pixel is the average of these values, summed in order of k), with
// every term written into `record` (render/sample_record.h).
Vec3 trace_pixel_sample(const RenderJob& job, int i, int j, int k, RayCounters& counters, SampleRecord& record);

struct RenderOutput {
    Film film;
    RayCounters counters;
    bool cancelled = false;  // true when progress.cancel stopped the loop: the film is incomplete
};

// Renders the image. Each pixel is the equal-weight average (box filter) of
// its spp samples; the result depends only on the scene, settings and seed,
// not on the thread count or scheduling.
RenderOutput render_image(const RenderJob& job, RenderProgress& progress);

}  // namespace sombra
