// `sombra explain` (spec §14): the story of one sample of one pixel, told
// from the SampleRecord that the integrators wrote while computing it
// (render/sample_record.h), as text for a reader, JSON for scripts and an
// SVG picture of the path in the scene beside the rendered image; under
// --denoise also the pixel denoised and the weights behind it (spec §25).
#pragma once

#include <algorithm>
#include <array>
#include <string>

#include "denoise/denoise.h"
#include "image/image_io.h"
#include "render/render.h"
#include "render/sample_record.h"
#include "scene/scene.h"

namespace sombra {

// What `explain --denoise` adds: the pixel as render --denoise gives it,
// with every weight the denoiser used, and as rendered before denoising.
struct DenoiseStory {
    DenoisedPixel pixel;
    std::array<float, 3> raw{};  // the pixel of the noisy image, the mean of all its samples
};

// What the story is about: the scene, the job that rendered it (image size,
// spp, integrator…), the file the scene came from and, under --denoise, the
// pixel's denoising (null without: the story is then spec §14's alone).
struct ExplainContext {
    const Scene& scene;
    const RenderJob& job;
    std::string scene_file;
    const DenoiseStory* denoised = nullptr;
};

// The story as readable text, one section per step, ending with the value
// (and then, under --denoise, the denoised pixel and its ten largest terms).
std::string explain_text(const ExplainContext& context, const SampleRecord& record);

// The same as one JSON object: "pixel", "sample", "value" (the exact floats),
// "camera_ray", "hit" (null on a miss), "lights" (the first vertex's), and
// "vertices" (every vertex; one under `direct`); under --denoise also
// "denoise" (spec §25: "value", "raw", "clamped" and every term's weights).
std::string explain_json(const ExplainContext& context, const SampleRecord& record);

// The samples per pixel of the render drawn beside the story: the scene's,
// at most 16. The picture needs only to show the scene, and a 4096-spp
// scene's explanation should not take as long as its render.
inline constexpr int kPictureMaxSpp = 16;
inline int picture_spp(const RenderSettings& settings) { return std::min(settings.spp, kPictureMaxSpp); }

// A picture of the story: the scene's outlines seen from beside the camera
// with the camera, the path, the lights and the shadow rays (blocked ones
// red, with the blocker marked), next to `image` (the render) with the pixel
// marked. `image` is the render at picture_spp samples, or under --denoise
// the one that was denoised (all its samples, before denoising), and then a
// map of the weights around the pixel is drawn beside it. A complete SVG document.
std::string explain_svg(const ExplainContext& context, const SampleRecord& record, ImageView image,
                        DisplayTransform display);

}  // namespace sombra
