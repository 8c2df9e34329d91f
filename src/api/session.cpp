#include "api/session.h"

#include <chrono>
#include <utility>
#include <vector>

#include "core/error.h"
#include "denoise/denoise.h"
#include "scene/animation.h"
#include "scene/texture_mipmap.h"

namespace sombra {

void prepare_textures(Scene& scene, const RenderSettings& settings) {
    if (settings.texture_filter == TextureFilter::Mipmap) build_mip_pyramids(scene.textures);
}

double frame_time(const Scene& scene, std::int64_t frame) {
    return static_cast<double>(frame) / (scene.animation ? scene.animation->fps : 24.0);
}

void move_to_frame(Scene& scene, std::optional<std::int64_t> frame, const std::string& source) {
    if (!scene.animation) return;
    set_scene_time(scene, frame_time(scene, frame.value_or(scene.animation->first_frame)), source);
}

void prepare_scene(Scene& scene, const RenderSettings& settings, const RenderOptions& options,
                   const std::string& source) {
    prepare_textures(scene, settings);  // the lookups must be the render's
    move_to_frame(scene, options.frame, source);
}

RenderJob make_job(const Scene& scene, const Accel& accel, const RenderSettings& settings, const RenderOptions& options,
                   std::chrono::steady_clock::time_point start) {
    RenderJob job = make_render_job(scene, accel, settings, options.threads, options.light_selection);
    job.limits = sampling_limits(options, start);
    job.aovs = options.aovs;
    if (options.crop) {
        job.window = options.crop;
        if (options.denoise) job.window = denoise_window(*options.crop, settings.width, settings.height);
        // Adaptive sampling decides after each pass from 3 × 3 neighbourhoods (RenderJob::window_margin).
        if (options.noise_threshold)
            job.window_margin = (settings.spp + kAdaptivePassSamples - 1) / kAdaptivePassSamples;
    }
    if (options.denoise) {
        job.aovs.denoise = true;
        if (job.limits.deadline)
            *job.limits.deadline -=
                std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(
                    denoise_seconds_estimate(job.window ? job.window->width : settings.width,
                                             job.window ? job.window->height : settings.height, options.threads)));
    }
    return job;
}

PixelWindow denoise_window(const PixelWindow& crop, int width, int height) {
    const PixelRect r =
        denoise_source_rect({crop.x0, crop.y0, crop.x0 + crop.width, crop.y0 + crop.height}, width, height);
    return {r.x0, r.y0, r.width(), r.height()};
}

Film denoise_render(RenderOutput& rendered, const RenderJob& job, const RenderOptions& options,
                    const std::atomic<bool>* cancel) {
    std::vector<float> denoised = denoise_image(rendered.aovs.denoise, options.threads, cancel);
    if (denoised.empty()) return {};  // cancelled
    Film noisy = std::move(rendered.film);
    rendered.film = Film(noisy.width, noisy.height);
    rendered.film.rgb = std::move(denoised);
    if (options.crop && job.window && !(*job.window == *options.crop)) {
        cut_to_window(rendered, *job.window, *options.crop);
        RenderOutput noisy_window;
        noisy_window.film = std::move(noisy);
        cut_to_window(noisy_window, *job.window, *options.crop);
        noisy = std::move(noisy_window.film);
    }
    return noisy;
}

std::vector<std::string> render_warnings(const Scene& scene, const RenderSettings& settings,
                                         const RenderOptions& options) {
    std::vector<std::string> warnings;
    if (settings.integrator == IntegratorKind::Direct && needs_path_integrator(scene))
        warnings.emplace_back(
            "the direct integrator lights with point, spot and directional lights only: quad lights and the "
            "environment are only seen, mirror and glass reflect nothing from them; use --integrator path");
    if (settings.integrator == IntegratorKind::Direct && uses_media(scene))
        warnings.emplace_back("the direct integrator ignores media (spec §26); use --integrator path");
    if (!emits_light(scene))
        warnings.emplace_back(
            "nothing in the scene emits light (no light, no emitting material or medium, a black background): "
            "the image is black");
    if (options.noise_threshold && options.min_spp >= settings.spp)
        warnings.emplace_back("--noise-threshold cannot stop any pixel early: --min-spp " +
                              std::to_string(options.min_spp) + " is not below the " + std::to_string(settings.spp) +
                              " samples per pixel asked, so every pixel takes them all");
    return warnings;
}

void check_explain_pixel(int x, int y, int sample, const RenderSettings& s) {
    const std::string where = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
    if (x < 0 || x >= s.width || y < 0 || y >= s.height)
        throw Error(where, "outside the " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                               " image (columns 0 to " + std::to_string(s.width - 1) + ", rows 0 to " +
                               std::to_string(s.height - 1) + ")");
    if (sample < 0 || sample >= s.spp)
        throw Error("--sample", "sample " + std::to_string(sample) + " does not exist: the pixel has " +
                                    std::to_string(s.spp) + " sample" + (s.spp == 1 ? "" : "s") + " (0 to " +
                                    std::to_string(s.spp - 1) + ")");
}

SampleRecord record_pixel_sample(const RenderJob& job, int x, int y, int sample) {
    SampleRecord record;
    RayCounters counters;
    trace_pixel_sample(job, x, y, sample, counters, record);
    return record;
}

}  // namespace sombra
