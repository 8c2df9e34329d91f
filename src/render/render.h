// The render loop: every pixel's samples through the integrator onto the
// film, in parallel tiles.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "accel/accel.h"
#include "render/accumulation.h"
#include "render/camera.h"
#include "render/film.h"
#include "render/integrator.h"
#include "render/lights/lights.h"
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

// When a pixel stops taking samples (spec §18). With neither a deadline nor
// a threshold every pixel takes settings.spp samples, in one pass.
struct SamplingLimits {
    // --time: no pass starts that would, at the last pass's pace, end after this.
    std::optional<std::chrono::steady_clock::time_point> deadline;
    // --noise-threshold T > 0: a pixel stops once the estimated standard
    // error of its mean luminance (Accumulation::luminance_standard_error:
    // pooled over its 3 × 3 neighbourhood) is at most T · max(mean, 10⁻³); 0 = off.
    double noise_threshold = 0;
    int min_spp = 16;  // no pixel stops by the threshold before this many samples
    // Samples each pass adds to every pixel (the viewer's steps); 0 = as
    // pass_samples decides below (kTimedPassSamples, kAdaptivePassSamples or all).
    int pass_samples = 0;
};

// The samples each pass adds to every pixel still sampling: two under a
// time budget (the finest step §18 allows), four with adaptive sampling
// (its rule is checked less often, which lets fewer pixels stop on a lucky
// low-variance streak), and all of settings.spp at once otherwise.
inline constexpr int kTimedPassSamples = 2;
inline constexpr int kAdaptivePassSamples = 4;

// Share `index` of `count` of an image's pixels (spec §21's shards): the
// image in blocks of kShardBlock × kShardBlock pixels, numbered row by row,
// block b going to share b mod count, so that every share gets some of each
// part of the image. count 1: the whole image.
struct ShardSpec {
    int index = 0;
    int count = 1;
};
inline constexpr int kShardBlock = 32;

inline bool shard_owns(const ShardSpec& shard, int width, int i, int j) {
    const int blocks_per_row = (width + kShardBlock - 1) / kShardBlock;
    const std::int64_t block = std::int64_t{j / kShardBlock} * blocks_per_row + i / kShardBlock;
    return block % shard.count == shard.index;
}

// How many of a width × height image's pixels `shard` renders.
inline std::uint64_t shard_pixel_count(const ShardSpec& shard, int width, int height) {
    std::uint64_t n = 0;
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) n += shard_owns(shard, width, i, j) ? 1u : 0u;
    return n;
}

// A rectangle of the image: pixels x0 ≤ i < x0 + width, y0 ≤ j < y0 + height.
struct PixelWindow {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    bool operator==(const PixelWindow&) const = default;
};

struct RenderJob {
    const Scene* scene = nullptr;  // geometry must be the mesh `accel` was built over
    const Accel* accel = nullptr;
    Camera camera;
    LightSet lights;          // the scene's lights as the integrator samples them
    RenderSettings settings;  // image size, spp (the most any pixel takes), seed, integrator and depth
    SamplingLimits limits;
    AovSet aovs;      // the AOVs to gather beside the image
    int threads = 0;  // worker threads; 0 = all hardware threads
    ShardSpec shard;  // the pixels to render; the others stay black with no samples
    // Set: only the window's pixels, each exactly as in the whole image, and
    // the output (film, AOVs, counts) is the window's size: one block of an
    // MPI render (distributed/mpi_render.cpp), or --crop (spec §27). A shard
    // splits the window's pixels as it would an image of the window's size.
    std::optional<PixelWindow> window;
    // Pixels rendered around the window and dropped: adaptive sampling's
    // rule pools each pixel's 3 × 3 neighbours after every pass, so a pixel
    // depends on those up to one pixel further each pass; a margin of as
    // many pixels as there are passes keeps the window's pixels exact.
    int window_margin = 0;
    // Called on the render's thread after each pass that ran to its end (not
    // after a cancelled one) with what the passes have gathered and the
    // number of passes so far: the viewer publishes the image from here.
    // Empty (the default, `sombra render`): nothing is called.
    std::function<void(const Accumulation&, int passes)> on_pass;
};

// The job for rendering `scene` with `accel` at `settings`, with the scene's
// camera resolved for that image size and its lights gathered for the
// integrator (under `path` the background is a constant environment light),
// emitters chosen as `light_selection` says (render/lights/lights.h).
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
    AovImages aovs;                   // those job.aovs asked for
    std::uint64_t samples = 0;        // taken over all pixels
    std::uint32_t min_pixel_spp = 0;  // the fewest and most samples a pixel took
    std::uint32_t max_pixel_spp = 0;
    std::uint64_t pixels = 0;  // rendered: the image's, or a shard's share of them
    int passes = 0;
    RayCounters counters;
    bool cancelled = false;  // true when progress.cancel stopped the loop: the film is incomplete
};

// The values of the pixels of `kept` among `values`, which hold `area`'s
// pixels top row first, each with the same number of channels, interleaved.
std::vector<float> window_values(const std::vector<float>& values, const PixelWindow& area, const PixelWindow& kept);

// Keeps the pixels of `kept` of everything `out` holds over `area` (film,
// AOVs, the denoiser's layers), top row first: --crop's image from a
// render of a larger window.
void cut_to_window(RenderOutput& out, const PixelWindow& area, const PixelWindow& kept);

// Renders the image in passes (spec §18). Each pixel is the equal-weight
// average (box filter) of its samples, taken in index order 0, 1, 2, …, so
// a pixel that took n samples equals the same pixel rendered at spp n. The
// result depends only on the scene, settings, seed and limits (and, under
// a deadline, on how many passes fit), not on the thread count or scheduling.
RenderOutput render_image(const RenderJob& job, RenderProgress& progress);

}  // namespace sombra
