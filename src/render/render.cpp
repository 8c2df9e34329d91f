#include "render/render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <limits>
#include <optional>

#include "core/flush_denormals.h"
#include "render/first_hit.h"
#include "render/ray_cone.h"
#include "render/sampler.h"

namespace sombra {

namespace {

// Square tiles keep neighbouring rays together (cache-friendly traversal)
// and are large enough that scheduling costs nothing.
constexpr int kTileSize = 16;

// Where sample k of pixel (i, j) goes: its position in the pixel, the
// image-plane point, the lens point and the camera ray.
struct CameraSample {
    PixelSample offset;
    float s = 0, t = 0;
    SampleStream::Pair lens{0.5f, 0.5f};  // (0.5, 0.5) is the lens centre; drawn only with an open aperture
    Ray ray;
};

CameraSample camera_sample(const RenderJob& job, std::uint64_t key, int i, int j, std::uint32_t k) {
    const RenderSettings& rs = job.settings;
    CameraSample c;
    c.offset = pixel_sample(k, static_cast<std::uint32_t>(rs.spp), key);
    c.s = image_plane_s(static_cast<float>(i) + c.offset.x, rs.width);
    c.t = image_plane_t(static_cast<float>(j) + c.offset.y, rs.height);
    if (job.camera.lens_radius > 0.0f) {
        c.lens = SampleStream{key, k, static_cast<std::uint32_t>(rs.spp)}.lens_2d();
        c.ray = camera_ray(job.camera, c.s, c.t, c.lens.u1, c.lens.u2);
    } else {
        c.ray = camera_ray(job.camera, c.s, c.t);
    }
    return c;
}

template <class... Record>
Vec3 trace_sample(const RenderJob& job, const IntegratorContext& ctx, std::uint64_t key, const Ray& ray,
                  std::uint32_t k, RayCounters& counters, Record&... record) {
    const RenderSettings& s = job.settings;
    if (s.integrator == IntegratorKind::Path) {
        SampleStream samples{key, k, static_cast<std::uint32_t>(s.spp)};
        return trace_path(ctx, ray, samples, counters, record...);
    }
    return trace_direct(ctx, ray, counters, record...);
}

// Adds samples count … end − 1 of image pixel (i, j), entry `pixel` of the
// accumulation, to it; a pixel that has reached the spp is done.
void sample_pixel(const RenderJob& job, const IntegratorContext& ctx, Accumulation& acc, std::size_t pixel, int i,
                  int j, std::uint32_t end, RayCounters& counters) {
    const RenderSettings& s = job.settings;
    const std::uint64_t key = pixel_key(s.seed, i, j, s.width);
    const bool first_hits = job.aovs.needs_first_hit();
    for (std::uint32_t k = acc.count(pixel); k < end; ++k) {
        const Ray ray = camera_sample(job, key, i, j, k).ray;
        if (first_hits) {
            FirstHit first;
            const Vec3 radiance = trace_sample(job, ctx, key, ray, k, counters, first);
            acc.add(pixel, radiance, &first);
        } else {
            acc.add(pixel, trace_sample(job, ctx, key, ray, k, counters), nullptr);
        }
    }
    if (acc.count(pixel) >= static_cast<std::uint32_t>(s.spp)) acc.finish(pixel);
}

// Spec §18's adaptive rule after a pass, for every pixel still sampling:
// decided from the pass's finished sums only (a separate loop), so that the
// decisions do not depend on the order pixels were rendered in.
void stop_converged_pixels(const RenderJob& job, Accumulation& acc) {
    const double threshold = job.limits.noise_threshold;
    const auto min_spp = static_cast<std::uint32_t>(std::max(job.limits.min_spp, 2));
    std::vector<std::uint8_t> stop(acc.pixels(), 0);
    tbb::parallel_for(0, acc.height(), [&](int j) {
        for (int i = 0; i < acc.width(); ++i) {
            const std::size_t pixel = acc.index(i, j);
            if (acc.done(pixel) || acc.count(pixel) < min_spp) continue;
            stop[pixel] = acc.luminance_standard_error(i, j) <=
                          threshold * std::max(acc.luminance_mean(pixel), Accumulation::kLuminanceFloor);
        }
    });
    for (std::size_t p = 0; p < stop.size(); ++p)
        if (stop[p]) acc.finish(p);
}

// `w` grown by `margin` pixels on each side, within the width × height image.
PixelWindow grown_window(const PixelWindow& w, int margin, int width, int height) {
    const int x0 = std::max(0, w.x0 - margin), y0 = std::max(0, w.y0 - margin);
    const int x1 = std::min(width, w.x0 + w.width + margin), y1 = std::min(height, w.y0 + w.height + margin);
    return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace

std::vector<float> window_values(const std::vector<float>& values, const PixelWindow& area, const PixelWindow& kept) {
    if (values.empty()) return {};
    const std::size_t channels =
        values.size() / (static_cast<std::size_t>(area.width) * static_cast<std::size_t>(area.height));
    std::vector<float> inside;
    inside.reserve(static_cast<std::size_t>(kept.width) * static_cast<std::size_t>(kept.height) * channels);
    for (int j = kept.y0; j < kept.y0 + kept.height; ++j) {
        const std::size_t row = static_cast<std::size_t>(j - area.y0) * static_cast<std::size_t>(area.width) +
                                static_cast<std::size_t>(kept.x0 - area.x0);
        inside.insert(inside.end(), values.begin() + static_cast<std::ptrdiff_t>(row * channels),
                      values.begin() +
                          static_cast<std::ptrdiff_t>((row + static_cast<std::size_t>(kept.width)) * channels));
    }
    return inside;
}

void cut_to_window(RenderOutput& out, const PixelWindow& area, const PixelWindow& kept) {
    const auto cut = [&](std::vector<float>& values) { values = window_values(values, area, kept); };
    cut(out.film.rgb);
    out.film.width = kept.width;
    out.film.height = kept.height;
    for (std::vector<float>* aov :
         {&out.aovs.albedo, &out.aovs.normal, &out.aovs.position, &out.aovs.depth, &out.aovs.spp, &out.aovs.variance})
        cut(*aov);
    DenoiseLayers& layers = out.aovs.denoise;
    if (layers.width == area.width && layers.height == area.height) {
        cut(layers.variance);
        for (int half = 0; half < 2; ++half)
            for (std::vector<float>* layer :
                 {&layers.color[half], &layers.albedo[half], &layers.normal[half], &layers.depth[half]})
                cut(*layer);
        layers.width = kept.width;
        layers.height = kept.height;
    }
}

namespace {

// How many samples each pass adds (see kTimedPassSamples).
std::uint32_t pass_samples(const RenderJob& job) {
    if (job.limits.pass_samples > 0) return static_cast<std::uint32_t>(job.limits.pass_samples);
    if (job.limits.noise_threshold > 0) return kAdaptivePassSamples;
    if (job.limits.deadline) return kTimedPassSamples;
    return static_cast<std::uint32_t>(job.settings.spp);
}

}  // namespace

RenderJob make_render_job(const Scene& scene, const Accel& accel, const RenderSettings& settings, int threads,
                          LightSelection light_selection) {
    RenderJob job;
    job.scene = &scene;
    job.accel = &accel;
    job.camera = make_camera(scene.camera, settings.width, settings.height);
    job.settings = settings;
    job.threads = threads;
    const bool path = settings.integrator == IntegratorKind::Path;
    Environment environment = scene.environment
                                  ? make_map_environment(scene.environment->image, scene.environment->scale,
                                                         scene.environment->rotate_y_degrees)
                                  : make_constant_environment(scene.background);
    job.lights = make_light_set(scene, std::move(environment), path, light_selection);
    return job;
}

IntegratorContext make_integrator_context(const RenderJob& job) {
    IntegratorContext ctx{job.scene, job.accel, &job.lights, job.settings.max_depth};
    ctx.max_volume_depth = job.settings.max_volume_depth;
    if (job.settings.texture_filter == TextureFilter::Mipmap) {
        ctx.ray_cones = true;
        ctx.camera_pixel_area =
            camera_pixel_area(job.camera.left, job.camera.up, job.settings.width, job.settings.height);
        ctx.orthographic_camera = job.camera.orthographic;
    }
    return ctx;
}

Vec3 trace_pixel_sample(const RenderJob& job, int i, int j, int k, RayCounters& counters, SampleRecord& record) {
    const DenormalsFlushed flushed;  // as render_image's tiles are traced
    const std::uint64_t key = pixel_key(job.settings.seed, i, j, job.settings.width);
    const CameraSample c = camera_sample(job, key, i, j, static_cast<std::uint32_t>(k));
    record.pixel_x = i;
    record.pixel_y = j;
    record.sample = k;
    record.offset_x = c.offset.x;
    record.offset_y = c.offset.y;
    record.s = c.s;
    record.t = c.t;
    record.lens = job.camera.lens_radius > 0.0f;
    record.lens_u = c.lens.u1;
    record.lens_v = c.lens.u2;
    record.origin = c.ray.origin;
    record.direction = c.ray.dir;
    return trace_sample(job, make_integrator_context(job), key, c.ray, static_cast<std::uint32_t>(k), counters, record);
}

RenderOutput render_image(const RenderJob& job, RenderProgress& progress) {
    using Clock = std::chrono::steady_clock;
    const RenderSettings& rs = job.settings;
    // The pixels rendered: the window's, or the whole image's.
    const PixelWindow kept = job.window.value_or(PixelWindow{0, 0, rs.width, rs.height});
    const PixelWindow area = grown_window(kept, job.window_margin, rs.width, rs.height);
    Accumulation acc(area.width, area.height, job.limits.noise_threshold > 0, job.aovs);
    tbb::combinable<RayCounters> per_thread;
    const IntegratorContext ctx = make_integrator_context(job);
    const auto spp = static_cast<std::uint32_t>(rs.spp);
    const std::uint32_t step = pass_samples(job);

    const int threads = job.threads > 0 ? job.threads : tbb::task_arena::automatic;
    // oneTBB caps its workers at the hardware's thread count (and says so on
    // stderr) unless more are allowed explicitly; more threads than cores is
    // a legitimate request, e.g. to test determinism.
    std::optional<tbb::global_control> allow_more;
    if (threads > tbb::info::default_concurrency())
        allow_more.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    tbb::task_arena arena(threads);
    RenderOutput out;
    if (job.shard.count > 1)
        for (int j = 0; j < area.height; ++j)
            for (int i = 0; i < area.width; ++i)
                if (!shard_owns(job.shard, area.width, i, j)) acc.finish(acc.index(i, j));
    arena.execute([&] {
        // A window (an MPI block, 32 × 32) in 8 × 8 tiles: 16 of them, enough for a rank's threads.
        const int tile_size = job.window ? kTileSize / 2 : kTileSize;
        const tbb::blocked_range2d<int> image(area.y0, area.y0 + area.height, tile_size, area.x0, area.x0 + area.width,
                                              tile_size);
        for (std::uint32_t pass_end = std::min(step, spp);; pass_end = std::min(pass_end + step, spp)) {
            const auto pass_start = Clock::now();
            std::atomic<bool> any_left{false};
            tbb::parallel_for(image, [&](const tbb::blocked_range2d<int>& tile) {
                if (progress.cancel.load(std::memory_order_relaxed)) return;
                const DenormalsFlushed flushed;
                RayCounters& counters = per_thread.local();
                bool left = false;
                for (int j = tile.rows().begin(); j < tile.rows().end(); ++j) {
                    const std::uint64_t rays_before = counters.rays();
                    std::uint64_t samples = 0;
                    for (int i = tile.cols().begin(); i < tile.cols().end(); ++i) {
                        // Checked per pixel too: at thousands of samples a tile can take seconds.
                        if (progress.cancel.load(std::memory_order_relaxed)) return;
                        const std::size_t pixel = acc.index(i - area.x0, j - area.y0);
                        if (acc.done(pixel)) continue;
                        const std::uint32_t before = acc.count(pixel);
                        sample_pixel(job, ctx, acc, pixel, i, j, pass_end, counters);
                        samples += acc.count(pixel) - before;
                        left = left || !acc.done(pixel);
                    }
                    // Reported per tile row, so that the progress bar moves
                    // smoothly even when a tile takes seconds.
                    progress.samples_done.fetch_add(samples, std::memory_order_relaxed);
                    progress.rays_traced.fetch_add(counters.rays() - rays_before, std::memory_order_relaxed);
                }
                if (left) any_left.store(true, std::memory_order_relaxed);
            });
            ++out.passes;
            if (progress.cancel.load()) break;
            if (job.on_pass) job.on_pass(acc, out.passes);
            if (!any_left.load()) break;
            if (job.limits.noise_threshold > 0) stop_converged_pixels(job, acc);
            // The next pass takes about as long as this one (no longer: it
            // samples the same pixels or fewer).
            const auto now = Clock::now();
            if (job.limits.deadline && now + (now - pass_start) > *job.limits.deadline) break;
        }
    });

    out.aovs = acc.aov_images();
    out.film = acc.take_image();
    if (kept.width != area.width || kept.height != area.height) cut_to_window(out, area, kept);
    // Over the pixels kept: a shard's others have no samples by design.
    out.min_pixel_spp = std::numeric_limits<std::uint32_t>::max();
    for (int j = kept.y0; j < kept.y0 + kept.height; ++j)
        for (int i = kept.x0; i < kept.x0 + kept.width; ++i) {
            if (job.shard.count > 1 && !shard_owns(job.shard, area.width, i - area.x0, j - area.y0)) continue;
            const std::uint32_t n = acc.count(acc.index(i - area.x0, j - area.y0));
            ++out.pixels;
            out.samples += n;
            out.min_pixel_spp = std::min(out.min_pixel_spp, n);
            out.max_pixel_spp = std::max(out.max_pixel_spp, n);
        }
    if (out.pixels == 0) out.min_pixel_spp = 0;
    per_thread.combine_each([&](const RayCounters& c) { out.counters += c; });
    out.cancelled = progress.cancel.load();
    return out;
}

}  // namespace sombra
