#include "measure.h"

#include <algorithm>
#include <utility>

#include "core/error.h"
#include "render/camera.h"
#include "render/integrator.h"
#include "render/render.h"

namespace sombra::bench {

namespace {

struct Round {
    double build_seconds = 0;
    double render_seconds = 0;
    std::size_t accel_bytes = 0;
    RenderOutput output;
};

Round build_and_render(const Scene& scene, const RenderSettings& settings, AccelKind kind,
                       const EmbreeSettings& embree) {
    Round round;
    const auto build_start = Clock::now();
    const Accel accel = make_compared_accel(scene, kind, embree);
    round.build_seconds = seconds_since(build_start);
    round.accel_bytes = accel_memory_bytes(accel);

    const RenderJob job = make_render_job(scene, accel, settings);
    RenderProgress progress;
    const auto render_start = Clock::now();
    round.output = render_image(job, progress);
    round.render_seconds = seconds_since(render_start);
    return round;
}

// The radiance at the centres of sampled pixels, traced through the BVH and
// through the brute-force loop (bench_util.h): they must agree to the last
// bit in theory, and within compare_films' tolerance here.
ImageAgreement direct_bvh_against_brute(const Scene& scene, const RenderSettings& settings) {
    const Accel bvh = make_accel(scene, AccelKind::Bvh);
    const Camera camera = make_camera(scene.camera, settings.width, settings.height);
    const LightSet lights = make_light_set(scene, make_constant_environment(scene.background), false);
    return bvh_against_brute(scene.geometry, bvh, settings.width, settings.height, 1.0 + double(scene.lights.size()),
                             64, [&](const Accel& accel, int i, int j) {
                                 const Ray ray = camera_ray(camera, image_plane_s(float(i) + 0.5f, settings.width),
                                                            image_plane_t(float(j) + 0.5f, settings.height));
                                 RayCounters counters;
                                 return trace_direct(IntegratorContext{&scene, &accel, &lights}, ray, counters);
                             });
}

}  // namespace

SceneMeasurement measure_scene(const Scene& scene, const RenderSettings& settings, int reps, const std::string& name,
                               const EmbreeSettings& embree) {
    const std::vector<AccelKind> kinds = compared_accels();
    SceneMeasurement m;
    m.triangles = scene.geometry.triangle_count();

    // The check, which also warms caches and thread pools for the rounds.
    std::vector<Film> films;
    for (const AccelKind kind : kinds) {
        const bool peak_reset = reset_peak_rss();
        Round round = build_and_render(scene, settings, kind, embree);
        BackendTiming timing;
        timing.kind = kind;
        timing.peak_rss_bytes = peak_reset ? peak_rss_since_reset_bytes() : 0;
        timing.rays = round.output.counters.camera_rays + round.output.counters.shadow_rays;
        timing.accel_bytes = round.accel_bytes;
        m.backends.push_back(timing);
        films.push_back(std::move(round.output.film));
    }
    m.agreement.pixels = films[0].rgb.size() / 3;
    m.agreement.equal = m.agreement.pixels;
    for (std::size_t k = 1; k < films.size(); ++k) {
        const ImageAgreement a = compare_films(films[0], films[k]);
        if (a.fraction() < m.agreement.fraction()) m.agreement = a;
        if (a.fraction() < kMinEqualFraction) {
            throw Error(name, accel_label(kinds[k], embree) + " and " + std::string(accel_name(kinds[0])) +
                                  " images differ in " + thousands(a.pixels - a.equal) + " of " + thousands(a.pixels) +
                                  " pixels (more than 0.1 %): not timing a wrong result");
        }
    }
    films.clear();

    m.brute_agreement = direct_bvh_against_brute(scene, settings);
    if (m.brute_agreement.equal != m.brute_agreement.pixels) {
        const ImageAgreement& a = m.brute_agreement;
        throw Error(name, "bvh and brute disagree at " + thousands(a.pixels - a.equal) + " of " + thousands(a.pixels) +
                              " sampled pixel centres: not timing a wrong result");
    }

    std::vector<std::vector<double>> builds(kinds.size()), renders(kinds.size());
    for (int rep = 0; rep < reps; ++rep) {
        for (std::size_t i = 0; i < kinds.size(); ++i) {
            const std::size_t k = rep % 2 == 0 ? i : kinds.size() - 1 - i;
            const Round round = build_and_render(scene, settings, kinds[k], embree);
            builds[k].push_back(round.build_seconds);
            renders[k].push_back(round.render_seconds);
        }
    }
    for (std::size_t k = 0; k < kinds.size(); ++k) {
        m.backends[k].build_seconds = median(builds[k]);
        m.backends[k].render_seconds = median(renders[k]);
    }
    return m;
}

}  // namespace sombra::bench
