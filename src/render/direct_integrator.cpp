#include "render/integrator.h"

#include <cmath>

#include "render/bsdf.h"
#include "render/interaction.h"
#include "render/delta_lights.h"
#include "render/ray_cone.h"
#include "render/sample_recorder.h"
#include "render/shading.h"

namespace sombra {

template <class Recorder>
void add_point_lights(const Scene& scene, const Accel& accel, const SurfaceInteraction& si, const Material& material,
                      const BsdfPoint& bsdf_point, Vec3 wo, Vec3 beta, Vec3& radiance, RayCounters& counters,
                      Recorder& recorder) {
    const ShadingView view{si, material, bsdf_point, wo};
    const Vec3 shadow_origin = offset_ray_origin(si.position, si.position_error, si.n_g);
    for (const PointLight& light : scene.lights) {
        const auto index = static_cast<std::uint32_t>(&light - scene.lights.data());  // for the recorder only
        const Vec3 to_light = light.position - si.position;
        const float distance_squared = dot(to_light, to_light);
        if (!(distance_squared > 0.0f)) {  // a light exactly on the surface lights nothing
            recorder.point_light(index, LightOutcome::OnSurface, view, Vec3{0.0f}, 0.0f, nullptr, Vec3{0.0f});
            continue;
        }
        const Vec3 wi = to_light / std::sqrt(distance_squared);
        // A light behind the surface (as seen from the viewer's side) adds nothing.
        if (dot(si.n_g, wi) <= 0.0f) {
            recorder.point_light(index, LightOutcome::Behind, view, wi, distance_squared, nullptr, Vec3{0.0f});
            continue;
        }

        // Shadow ray: from the offset origin to the light; t = 1 reaches the
        // light, and the bound just short of it keeps the light's own
        // position (possibly on a surface) from counting as an occluder.
        ++counters.shadow_rays;
        const Ray shadow{shadow_origin, light.position - shadow_origin, 1.0f - 1e-5f};
        if (occluded(accel, shadow)) {
            recorder.point_light(index, LightOutcome::Blocked, view, wi, distance_squared, &shadow, Vec3{0.0f});
            continue;
        }

        // L += I / |c − x|² · f_r(x, ω_i, ω_o) · |n_s · ω_i|
        const Vec3 f_r = eval_bsdf(material, bsdf_point, wo, wi);
        const Vec3 contribution = beta * (light.intensity * (std::fabs(dot(si.n_s, wi)) / distance_squared) * f_r);
        radiance += contribution;
        recorder.point_light(index, LightOutcome::Visible, view, wi, distance_squared, &shadow, contribution);
    }
}

template void add_point_lights<NoRecorder>(const Scene&, const Accel&, const SurfaceInteraction&, const Material&,
                                           const BsdfPoint&, Vec3, Vec3, Vec3&, RayCounters&, NoRecorder&);
template void add_point_lights<SampleRecorder>(const Scene&, const Accel&, const SurfaceInteraction&, const Material&,
                                               const BsdfPoint&, Vec3, Vec3, Vec3&, RayCounters&, SampleRecorder&);

namespace {

template <class Recorder>
Vec3 trace_direct_recorded(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters, Recorder& recorder) {
    const Scene& scene = *ctx.scene;
    ++counters.camera_rays;
    Hit hit;
    Vec3 radiance{0.0f};
    if (!intersect(*ctx.accel, ray, hit)) {
        // A miss sees the background or the environment map (only seen, spec §10).
        radiance = eval_environment(ctx.lights->environment, normalize(ray.dir));
        recorder.escaped(ray, Vec3{1.0f}, radiance, 1.0f, 0.0f, 0.0f);
        recorder.end("the camera ray left the scene");
    } else {
        SurfaceInteraction si = make_surface_interaction(scene.geometry, ray, hit);
        Material textured;
        const RayCone cone = ctx.ray_cones ? camera_ray_cone(ctx.camera_pixel_area, ray.dir) : RayCone{};
        const float footprint = cone.active() ? surface_footprint(cone, hit.t * length(ray.dir), ray.dir, si.n_g) : 0.0f;
        const Material& material = resolve_material(scene, si, textured, footprint);
        const Vec3 wo = -normalize(ray.dir);
        recorder.surface(ray, hit, si, material, Vec3{1.0f});

        // Emission is seen only directly (spec §4, §9).
        radiance = emitted_radiance(material, si);
        recorder.emission(radiance, 1.0f, 0.0f, 0.0f, radiance);
        // Delta BSDFs (mirror, glass) reflect nothing from a point light.
        if (!is_delta_bsdf(material)) {
            add_point_lights(scene, *ctx.accel, si, material, make_bsdf_point(si.n_g, si.n_s, si.outside), wo,
                             Vec3{1.0f}, radiance, counters, recorder);
        } else {
            recorder.delta_material();
        }
        recorder.end("the direct integrator stops at the first surface");
    }

    const bool finite = is_finite(radiance);
    if (!finite) {
        ++counters.nonfinite_samples;
        radiance = Vec3{0.0f};
    }
    recorder.value(radiance, !finite);
    return radiance;
}

}  // namespace

Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters) {
    NoRecorder none;
    return trace_direct_recorded(ctx, ray, counters, none);
}

Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters, SampleRecord& record) {
    SampleRecorder recorder(*ctx.scene, *ctx.accel, record);
    return trace_direct_recorded(ctx, ray, counters, recorder);
}

}  // namespace sombra
