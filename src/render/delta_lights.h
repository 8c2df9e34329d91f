// Next-event estimation for the delta lights (spec §4, §16): point, spot and
// directional lights, each visited at every vertex with one shadow ray.
// Shared by both integrators so that `path` at max_depth 1 gives `direct`'s
// pixels.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "accel/accel.h"
#include "render/bsdf/bsdf.h"
#include "render/interaction.h"
#include "render/lights/lights.h"
#include "render/ray_counters.h"
#include "render/sample_record.h"
#include "render/shading_view.h"

namespace sombra {

// Adds to `radiance`, for every delta light of `lights` on the viewer's side
// of n_g and not blocked, beta · f(ω_o, ω_i) · |n_s·ω_i| times what arrives:
// I/|c−x|² from a point light, I·s²/|c−x|² from a spot (s its falloff at
// ω_i, scene/light.h; nothing outside its cone, without a shadow ray), E
// from a directional light (shadow ray unbounded). One shadow ray per light
// that can contribute. The arithmetic is ordered as that formula reads, and
// for a point light with beta = 1 it is exactly version 1's. `recorder`
// (render/sample_recorder.h: NoRecorder or SampleRecorder) hears every
// light's outcome. Defined here, so that each integrator inlines it and no
// hit pays for a call's prologue and the spills of its eleven arguments.
template <class Recorder>
void add_delta_lights(const LightSet& lights, const Accel& accel, const SurfaceInteraction& si,
                      const Material& material, const BsdfPoint& bsdf_point, Vec3 wo, Vec3 beta, Vec3& radiance,
                      RayCounters& counters, Recorder& recorder) {
    const ShadingView view{si, material, bsdf_point, wo};
    const Vec3 shadow_origin = offset_ray_origin(si.position, si.position_error, si.n_g);
    constexpr float kUnbounded = std::numeric_limits<float>::infinity();
    // The light array read through a pointer and a count held in locals:
    // through `lights.delta` the loop would load and divide the vector's
    // ends again after every shadow ray (occluded() might, for all the
    // compiler knows, have changed them).
    const PunctualLight* const delta = lights.delta.data();
    const auto count = static_cast<std::uint32_t>(lights.delta.size());
    for (std::uint32_t index = 0; index < count; ++index) {
        const PunctualLight& light = delta[index];
        const bool directional = light.type == LightType::Directional;
        // Where the light arrives from: ω_i, the squared distance (+∞ for a
        // directional light, as the recorder reports it) and the
        // inverse-square divisor (1 for a directional light: E has no falloff).
        Vec3 wi;
        float distance_squared = kUnbounded, divisor = 1.0f;
        if (directional) {
            // From infinitely far: the light arrives along `direction` everywhere.
            wi = -light.direction;
        } else {
            const Vec3 to_light = light.position - si.position;
            distance_squared = dot(to_light, to_light);
            if (!(distance_squared > 0.0f)) {  // a light exactly on the surface lights nothing
                recorder.delta_light(index, LightOutcome::OnSurface, view, Vec3{0.0f}, 0.0f, nullptr, Vec3{0.0f});
                continue;
            }
            wi = to_light / std::sqrt(distance_squared);
            divisor = distance_squared;
        }
        // A light behind the surface (as seen from the viewer's side) adds
        // nothing, unless the material lets light through (a rough thin
        // transmissive pbr): its shadow ray then leaves from the back.
        const bool behind = dot(si.n_g, wi) <= 0.0f;
        if (behind && !transmits_diffusely(material)) {
            recorder.delta_light(index, LightOutcome::Behind, view, wi, distance_squared, nullptr, Vec3{0.0f});
            continue;
        }
        // A spot sends I·s² along −ω_i; outside its cone nothing, and no shadow ray is needed.
        Vec3 intensity = light.intensity;
        if (light.type == LightType::Spot) {
            const float falloff = spot_falloff(light, -dot(light.direction, wi));
            if (!(falloff > 0.0f)) {
                recorder.delta_light(index, LightOutcome::OutsideCone, view, wi, distance_squared, nullptr, Vec3{0.0f});
                continue;
            }
            intensity = light.intensity * falloff;
        }

        // The shadow ray, made only for a light that can contribute. A
        // directional light's has no end; a point or spot light's goes from
        // the offset origin to the light: t = 1 reaches it, and the bound
        // just short of it keeps the light's own position (possibly on a
        // surface) from counting as an occluder.
        const Vec3 origin = behind ? offset_ray_origin(si.position, si.position_error, -si.n_g) : shadow_origin;
        const Ray shadow = directional ? Ray{origin, wi} : Ray{origin, light.position - origin, 1.0f - 1e-5f};
        ++counters.shadow_rays;
        if (occluded(accel, shadow)) {
            recorder.delta_light(index, LightOutcome::Blocked, view, wi, distance_squared, &shadow, Vec3{0.0f});
            continue;
        }

        // L += I / |c − x|² · f_r(x, ω_i, ω_o) · |n_s · ω_i|   (a spot's I carries s²; a sun's E divided by 1, exactly)
        const Vec3 f_r = eval_bsdf(material, bsdf_point, wo, wi);
        const Vec3 contribution = beta * (intensity * (std::fabs(dot(si.n_s, wi)) / divisor) * f_r);
        radiance += contribution;
        recorder.delta_light(index, LightOutcome::Visible, view, wi, distance_squared, &shadow, contribution);
    }
}

}  // namespace sombra
