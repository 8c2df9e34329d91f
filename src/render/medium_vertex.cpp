#include "render/medium_vertex.h"

#include "render/first_hit.h"
#include "render/lights/delta_light_types.h"
#include "render/lights/lights.h"
#include "render/media/phase_function.h"
#include "render/sample_recorder.h"
#include "render/shadow_ray.h"

namespace sombra {

template <class Recorder>
Vec3 medium_direct_light(const IntegratorContext& ctx, std::uint32_t medium_index, Vec3 x, Vec3 d_in, float u_choice,
                         float u1, float u2, RayCounters& counters, TrackingRng& rng, Recorder& recorder) {
    const LightSet& lights = *ctx.lights;
    const Medium& medium = ctx.scene->media[medium_index];
    // What arrives along a shadow ray from x (0 where a surface blocks it).
    auto arriving = [&](const Ray& shadow) {
        ++counters.shadow_rays;
        return shadow_transmittance(*ctx.accel, *ctx.scene, shadow, medium_index, true, &rng);
    };
    Vec3 total{0.0f};
    const auto count = static_cast<std::uint32_t>(lights.delta.size());
    for (std::uint32_t index = 0; index < count; ++index) {
        const PunctualLight& light = lights.delta[index];
        const DeltaArrival a = delta_arrival(light, x);
        const float phase = henyey_greenstein(medium.g, dot(d_in, a.wi));
        if (on_surface(a)) {
            recorder.medium_delta_light(index, LightOutcome::OnSurface, a, phase, nullptr, Vec3{0.0f}, Vec3{0.0f});
            continue;
        }
        const float factor = delta_factor(light, a.wi);
        if (!(factor > 0.0f)) {
            recorder.medium_delta_light(index, LightOutcome::OutsideCone, a, phase, nullptr, Vec3{0.0f}, Vec3{0.0f});
            continue;
        }
        const Ray shadow = delta_shadow_ray(light, a, x);
        const Vec3 transmittance = arriving(shadow);
        if (!(max_component(transmittance) > 0.0f)) {
            recorder.medium_delta_light(index, LightOutcome::Blocked, a, phase, &shadow, transmittance, Vec3{0.0f});
            continue;
        }
        const Vec3 term = incident_radiance_factor(light, a, factor) * phase * transmittance;
        total += term;
        recorder.medium_delta_light(index, LightOutcome::Visible, a, phase, &shadow, transmittance, term);
    }
    if (!lights.has_sampled_lights() || ctx.strategy == LightStrategy::BsdfOnly) return total;
    LightSample ls;
    if (!sample_light(lights, *ctx.scene, x, Vec3{0.0f}, u_choice, u1, u2, ls)) {
        recorder.medium_sampled_light(nullptr, x, 0.0f, nullptr, Vec3{0.0f}, 0.0f, Vec3{0.0f});
        return total;
    }
    const float phase = henyey_greenstein(medium.g, dot(d_in, ls.wi));
    const float weight = ctx.strategy == LightStrategy::Mis ? power_heuristic(ls.pdf, phase) : 1.0f;
    const Ray shadow = ls.at_infinity ? Ray{x, ls.wi} : Ray{x, ls.target - x, 1.0f - 1e-4f};
    const Vec3 transmittance = arriving(shadow);
    if (!(max_component(transmittance) > 0.0f)) {
        recorder.medium_sampled_light(&ls, x, phase, &shadow, transmittance, weight, Vec3{0.0f});
        return total;
    }
    const Vec3 term = ls.radiance * transmittance * (phase * weight / ls.pdf);
    recorder.medium_sampled_light(&ls, x, phase, &shadow, transmittance, weight, term);
    return total + term;
}

template Vec3 medium_direct_light(const IntegratorContext&, std::uint32_t, Vec3, Vec3, float, float, float,
                                  RayCounters&, TrackingRng&, NoRecorder&);
template Vec3 medium_direct_light(const IntegratorContext&, std::uint32_t, Vec3, Vec3, float, float, float,
                                  RayCounters&, TrackingRng&, FirstHitRecorder&);
template Vec3 medium_direct_light(const IntegratorContext&, std::uint32_t, Vec3, Vec3, float, float, float,
                                  RayCounters&, TrackingRng&, SampleRecorder&);

}  // namespace sombra
