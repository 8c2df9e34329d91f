#include "render/medium_vertex.h"

#include "render/lights/delta_light_types.h"
#include "render/lights/lights.h"
#include "render/media/phase_function.h"
#include "render/shadow_ray.h"

namespace sombra {

Vec3 medium_direct_light(const IntegratorContext& ctx, std::uint32_t medium_index, Vec3 x, Vec3 d_in,
                         float u_choice, float u1, float u2, RayCounters& counters, TrackingRng& rng) {
    const LightSet& lights = *ctx.lights;
    const Medium& medium = ctx.scene->media[medium_index];
    // What arrives along a shadow ray from x (0 where a surface blocks it).
    auto arriving = [&](const Ray& shadow) {
        ++counters.shadow_rays;
        return shadow_transmittance(*ctx.accel, *ctx.scene, shadow, medium_index, true, &rng);
    };
    Vec3 total{0.0f};
    for (const PunctualLight& light : lights.delta) {
        const DeltaArrival a = delta_arrival(light, x);
        if (on_surface(a)) continue;
        const float factor = delta_factor(light, a.wi);
        if (!(factor > 0.0f)) continue;
        const Vec3 transmittance = arriving(delta_shadow_ray(light, a, x));
        if (!(max_component(transmittance) > 0.0f)) continue;
        total += incident_radiance_factor(light, a, factor) * henyey_greenstein(medium.g, dot(d_in, a.wi)) *
                 transmittance;
    }
    if (!lights.has_sampled_lights() || ctx.strategy == LightStrategy::BsdfOnly) return total;
    LightSample ls;
    if (!sample_light(lights, *ctx.scene, x, Vec3{0.0f}, u_choice, u1, u2, ls)) return total;
    const float phase = henyey_greenstein(medium.g, dot(d_in, ls.wi));
    const Vec3 transmittance = arriving(ls.at_infinity ? Ray{x, ls.wi} : Ray{x, ls.target - x, 1.0f - 1e-4f});
    if (!(max_component(transmittance) > 0.0f)) return total;
    const float weight = ctx.strategy == LightStrategy::Mis ? power_heuristic(ls.pdf, phase) : 1.0f;
    return total + ls.radiance * transmittance * (phase * weight / ls.pdf);
}

}  // namespace sombra
