// The Embree yardstick's image test, shared by embree_test.cpp (whole
// scenes) and embree_instancing_test.cpp (through instances): one render
// through the BVH and one through Embree, compared pixel by pixel.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/accel.h"
#include "render/render.h"

namespace sombra::testing {

// Equal to a thousandth (relative, with a floor of 1e-2 below which
// values count as dark): Embree's hits agree with the BVH's only to float
// rounding (accel/embree_backend.h).
inline bool same_pixel(const float* a, const float* b) {
    for (int c = 0; c < 3; ++c) {
        if (std::fabs(a[c] - b[c]) > 1e-3f * std::max({std::fabs(a[c]), std::fabs(b[c]), 1e-2f})) return false;
    }
    return true;
}

struct ImageAgreement {
    std::size_t pixels = 0;
    std::size_t differing = 0;  // pixels not same_pixel
    std::size_t lit = 0;        // pixels of the BVH's image brighter than 0.05 (summed RGB)
    std::uint64_t bvh_camera_rays = 0, embree_camera_rays = 0;
};

// `scene` rendered at `settings` by the direct integrator's job through the
// BVH and through Embree.
inline ImageAgreement compare_bvh_with_embree(const Scene& scene, const RenderSettings& settings) {
    RenderJob job;
    job.scene = &scene;
    job.settings = settings;
    job.camera = make_camera(scene.camera, settings.width, settings.height);
    job.lights = make_light_set(scene, make_constant_environment(scene.background), false);
    std::vector<RenderOutput> images;
    for (const AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
        const Accel accel = make_accel(scene, kind);
        job.accel = &accel;
        RenderProgress progress;
        images.push_back(render_image(job, progress));
    }
    const std::vector<float>& a = images[0].film.rgb;
    const std::vector<float>& b = images[1].film.rgb;
    ImageAgreement result;
    result.bvh_camera_rays = images[0].counters.camera_rays;
    result.embree_camera_rays = images[1].counters.camera_rays;
    if (a.size() != b.size()) return result;  // pixels 0: the callers' check fails
    result.pixels = a.size() / 3;
    for (std::size_t p = 0; p < result.pixels; ++p) {
        result.differing += !same_pixel(&a[3 * p], &b[3 * p]);
        result.lit += a[3 * p] + a[3 * p + 1] + a[3 * p + 2] > 0.05f;
    }
    return result;
}

}  // namespace sombra::testing
