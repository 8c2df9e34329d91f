// The steps between a loaded scene and its pixels that every front end
// takes alike (the command line, Python, the viewer): the scene made ready
// for the settings and moved to its frame, the render job built from the
// options, and one pixel's sample traced for explain (spec §14).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "api/render_options.h"
#include "render/render.h"
#include "render/sample_record.h"
#include "scene/scene.h"

namespace sombra {

// What the textures need for `settings`: their mip pyramids under
// TextureFilter::Mipmap (scene/texture_mipmap.h), nothing otherwise.
void prepare_textures(Scene& scene, const RenderSettings& settings);

// The moment of `frame` in seconds: frame / fps (24 without an "animation").
double frame_time(const Scene& scene, std::int64_t frame);

// Moves an animated scene to `frame`'s moment, or to its first frame's
// (spec §22); a scene without animation is left as it is. `source` names
// the scene in errors. Throws Error.
void move_to_frame(Scene& scene, std::optional<std::int64_t> frame, const std::string& source);

// The textures prepared and the scene moved to options.frame: what a
// still render or explain needs before building the acceleration structure.
void prepare_scene(Scene& scene, const RenderSettings& settings, const RenderOptions& options,
                   const std::string& source);

// The job that renders `scene` at `settings` as `options` ask (threads,
// emitter choice, sampling limits counted from `start`, AOVs). Under
// options.denoise the job also gathers the denoiser's layers, and a time
// budget keeps back what the denoiser is expected to take (spec §25).
RenderJob make_job(const Scene& scene, const Accel& accel, const RenderSettings& settings, const RenderOptions& options,
                   std::chrono::steady_clock::time_point start);

// What make_job renders for a --crop window under --denoise (spec §27): the
// window grown by the denoiser's reach, so that denoising it gives the
// window's pixels as denoising the whole image does (denoise_source_rect).
PixelWindow denoise_window(const PixelWindow& crop, int width, int height);

// Spec §25: the film of `rendered` (by `job`, which make_job made from
// `options` with options.denoise) replaced by the denoised image, on
// options.threads (the result is the same for any), then, with
// options.crop, everything cut from the grown window to the crop. Returns
// the film before denoising: the noisy AOV. Once `*cancel` is true the
// denoiser gives up: `rendered` keeps its film, and the Film returned is empty.
Film denoise_render(RenderOutput& rendered, const RenderJob& job, const RenderOptions& options,
                    const std::atomic<bool>* cancel = nullptr);

// What a render of `scene` at `settings` as `options` ask should warn of,
// each one line without its place (the front end names the scene): the
// direct integrator's limits (spec §10, §26), nothing that emits light, and
// adaptive sampling that cannot stop any pixel early (spec §27).
std::vector<std::string> render_warnings(const Scene& scene, const RenderSettings& settings,
                                         const RenderOptions& options);

// Pixel (x, y) (column, row) and its sample `sample` checked against the
// image `settings` describe. Throws Error naming the pixel, or "--sample".
void check_explain_pixel(int x, int y, int sample, const RenderSettings& settings);

// Sample `sample` of pixel (x, y), traced as the render traces it, with
// every term recorded for explain.
SampleRecord record_pixel_sample(const RenderJob& job, int x, int y, int sample);

}  // namespace sombra
