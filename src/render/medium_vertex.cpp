#include "render/medium_vertex.h"

#include <cmath>
#include <limits>

#include "render/lights/delta_light_types.h"
#include "render/media/homogeneous_medium.h"
#include "render/media/phase_function.h"

namespace sombra {

Vec3 medium_direct_light(const IntegratorContext& ctx, const Medium& medium, Vec3 x, Vec3 d_in, float u_choice,
                         float u1, float u2, RayCounters& counters) {
    const LightSet& lights = *ctx.lights;
    Vec3 total{0.0f};
    for (const PunctualLight& light : lights.delta) {
        const DeltaArrival a = delta_arrival(light, x);
        if (on_surface(a)) continue;
        const float factor = delta_factor(light, a.wi);
        if (!(factor > 0.0f)) continue;
        const Ray shadow = delta_shadow_ray(light, a, x);
        ++counters.shadow_rays;
        if (occluded(*ctx.accel, shadow)) continue;
        const bool positioned = light_type_traits(light.type).positioned;
        const float distance = positioned ? std::sqrt(a.distance_squared) : std::numeric_limits<float>::infinity();
        total += incident_radiance_factor(light, a, factor) * henyey_greenstein(medium.g, dot(d_in, a.wi)) *
                 homogeneous_transmittance(medium, distance);
    }
    if (!lights.has_sampled_lights() || ctx.strategy == LightStrategy::BsdfOnly) return total;
    LightSample ls;
    if (!sample_light(lights, *ctx.scene, x, Vec3{0.0f}, u_choice, u1, u2, ls)) return total;
    const float phase = henyey_greenstein(medium.g, dot(d_in, ls.wi));
    ++counters.shadow_rays;
    const Ray shadow = ls.at_infinity ? Ray{x, ls.wi} : Ray{x, ls.target - x, 1.0f - 1e-4f};
    if (occluded(*ctx.accel, shadow)) return total;
    const float weight = ctx.strategy == LightStrategy::Mis ? power_heuristic(ls.pdf, phase) : 1.0f;
    return total + ls.radiance * homogeneous_transmittance(medium, shadow_length(ls.at_infinity, x, ls.target)) *
                       (phase * weight / ls.pdf);
}

}  // namespace sombra
