#include "render/integrator.h"

#include <cmath>

#include "render/bsdf.h"
#include "render/interaction.h"
#include "render/point_lights.h"
#include "render/shading.h"

namespace sombra {

void add_point_lights(const Scene& scene, const Accel& accel, const SurfaceInteraction& si, const Material& material,
                      const BsdfPoint& bsdf_point, Vec3 wo, Vec3 beta, Vec3& radiance, RayCounters& counters) {
    const Vec3 shadow_origin = offset_ray_origin(si.position, si.position_error, si.n_g);
    for (const PointLight& light : scene.lights) {
        const Vec3 to_light = light.position - si.position;
        const float distance_squared = dot(to_light, to_light);
        if (!(distance_squared > 0.0f)) continue;  // a light exactly on the surface lights nothing
        const Vec3 wi = to_light / std::sqrt(distance_squared);
        // A light behind the surface (as seen from the viewer's side) adds nothing.
        if (dot(si.n_g, wi) <= 0.0f) continue;

        // Shadow ray: from the offset origin to the light; t = 1 reaches the
        // light, and the bound just short of it keeps the light's own
        // position (possibly on a surface) from counting as an occluder.
        ++counters.shadow_rays;
        const Ray shadow{shadow_origin, light.position - shadow_origin, 1.0f - 1e-5f};
        if (occluded(accel, shadow)) continue;

        // L += I / |c − x|² · f_r(x, ω_i, ω_o) · |n_s · ω_i|
        const Vec3 f_r = eval_bsdf(material, bsdf_point, wo, wi);
        radiance += beta * (light.intensity * (std::fabs(dot(si.n_s, wi)) / distance_squared) * f_r);
    }
}

Vec3 trace_direct(const IntegratorContext& ctx, const Ray& ray, RayCounters& counters) {
    const Scene& scene = *ctx.scene;
    ++counters.camera_rays;
    Hit hit;
    // A miss sees the background or the environment map (only seen, spec §10).
    if (!intersect(*ctx.accel, ray, hit)) return eval_environment(ctx.lights->environment, normalize(ray.dir));

    SurfaceInteraction si = make_surface_interaction(scene.geometry, ray, hit);
    Material textured;
    const Material& material = resolve_material(scene, si, textured);
    const Vec3 wo = -normalize(ray.dir);

    // Emission is seen only directly (spec §4, §9).
    Vec3 radiance = emitted_radiance(material, si);
    // Delta BSDFs (mirror, glass) reflect nothing from a point light.
    if (!is_delta_bsdf(material))
        add_point_lights(scene, *ctx.accel, si, material, make_bsdf_point(si.n_g, si.n_s, si.outside), wo, Vec3{1.0f},
                         radiance, counters);

    if (!is_finite(radiance)) {
        ++counters.nonfinite_samples;
        return Vec3{0.0f};
    }
    return radiance;
}

}  // namespace sombra
