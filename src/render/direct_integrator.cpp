// The direct integrator of spec §4: what the camera ray sees, lit by the
// delta lights (point, spot, directional) only.
#include "render/integrator.h"

#include <cmath>

#include "render/bsdf/bsdf.h"
#include "render/delta_lights.h"
#include "render/first_hit.h"
#include "render/interaction.h"
#include "render/ray_cone.h"
#include "render/sample_recorder.h"
#include "render/shading.h"
#include "render/shadow_ray.h"

namespace sombra {

namespace {

// The radiance leaving the camera ray's hit `si` towards the camera, with
// `material` the material there (resolved for the hit where it has to be):
// what the surface emits, and what the delta lights send it.
template <class Recorder>
Vec3 shade_direct(const IntegratorContext& ctx, const Ray& ray, const Hit& hit, const SurfaceInteraction& si,
                  const Material& material, RayCounters& counters, Recorder& recorder) {
    const Vec3 wo = -normalize(ray.dir);
    recorder.surface(ray, hit, si, material, Vec3{1.0f});

    // Emission is seen only directly (spec §4, §9).
    Vec3 radiance = emitted_radiance(material, si);
    recorder.emission(radiance, 1.0f, 0.0f, 0.0f, radiance);
    // Delta BSDFs (mirror, glass) reflect nothing from a point light.
    // The direct integrator only evaluates the BSDF: no frame for a
    // diffuse or Phong surface, which would not read it.
    if (!is_delta_bsdf(material)) {
        // Shadow rays cross interface surfaces; media are ignored (spec §26).
        const ShadowMedia interfaces{ctx.scene, MediumSides{}, false};
        add_delta_lights(*ctx.lights, *ctx.accel, si, material,
                         make_eval_bsdf_point(material, si.n_g, si.n_s, si.outside, si.n_c), wo, Vec3{1.0f}, radiance,
                         counters, recorder, ctx.scene->interface_material != kNoInterface ? &interfaces : nullptr);
    } else {
        recorder.delta_material();
    }
    recorder.end("the direct integrator stops at the first surface");
    return radiance;
}

template <class Recorder>
Vec3 trace_direct_recorded(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters, Recorder& recorder) {
    const Scene& scene = *ctx.scene;
    ++counters.camera_rays;
    Hit hit;
    Vec3 radiance{0.0f};
    if (!intersect_past_interfaces(*ctx.accel, scene, ray, hit)) {
        // A miss sees the background or the environment map (only seen, spec §10).
        radiance = eval_environment(ctx.lights->environment, normalize(ray.dir));
        recorder.escaped(ray, Vec3{1.0f}, radiance, 1.0f, 0.0f, 0.0f);
        recorder.end("the camera ray left the scene");
    } else {
        SurfaceInteraction si = make_surface_interaction(scene, ray, hit);
        if (needs_resolved_material(scene, si)) {
            // Textures are read at the hit, filtered over the ray cone's
            // footprint when mip-mapping (render/ray_cone.h).
            const RayCone cone =
                ctx.ray_cones ? camera_ray_cone(ctx.camera_pixel_area, ray.dir, ctx.orthographic_camera) : RayCone{};
            const float footprint =
                cone.active() ? surface_footprint(cone, hit.t * length(ray.dir), ray.dir, si.n_g) : 0.0f;
            Material textured;
            const Material& material = resolve_material(scene, si, textured, footprint);
            radiance = shade_direct(ctx, ray, hit, si, material, counters, recorder);
        } else {
            // The scene's material itself: an untextured hit constructs no
            // Material of its own (one per camera ray, ~500 bytes each).
            radiance = shade_direct(ctx, ray, hit, si, scene.materials[si.material], counters, recorder);
        }
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
    SampleRecorder recorder(*ctx.scene, *ctx.lights, *ctx.accel, record);
    return trace_direct_recorded(ctx, ray, counters, recorder);
}

Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters, FirstHit& first) {
    FirstHitRecorder recorder(first);
    return trace_direct_recorded(ctx, ray, counters, recorder);
}

}  // namespace sombra
