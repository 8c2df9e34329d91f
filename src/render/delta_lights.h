// Next-event estimation for the delta lights (spec §4, §16): point, spot and
// directional lights, each visited at every vertex with one shadow ray.
// Shared by both integrators so that `path` at max_depth 1 gives `direct`'s
// pixels.
#pragma once

#include <cmath>
#include <cstdint>

#include "accel/accel.h"
#include "render/bsdf/bsdf.h"
#include "render/interaction.h"
#include "render/lights/delta_light_types.h"
#include "render/lights/lights.h"
#include "render/ray_counters.h"
#include "render/sample_record.h"
#include "render/shading_view.h"
#include "render/shadow_ray.h"

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
// With `media` (spec §26: the scene has media or interface surfaces) each
// shadow ray crosses interfaces and each light's term is multiplied by the
// transmittance along its shadow ray.
template <class Recorder>
void add_delta_lights(const LightSet& lights, const Accel& accel, const SurfaceInteraction& si,
                      const Material& material, const BsdfPoint& bsdf_point, Vec3 wo, Vec3 beta, Vec3& radiance,
                      RayCounters& counters, Recorder& recorder, const ShadowMedia* media = nullptr) {
    const ShadingView view{si, material, bsdf_point, wo};
    const Vec3 shadow_origin = offset_ray_origin(si.position, si.position_error, si.n_g);
    // The light array read through a pointer and a count held in locals:
    // through `lights.delta` the loop would load and divide the vector's
    // ends again after every shadow ray (occluded() might, for all the
    // compiler knows, have changed them).
    const PunctualLight* const delta = lights.delta.data();
    const auto count = static_cast<std::uint32_t>(lights.delta.size());
    for (std::uint32_t index = 0; index < count; ++index) {
        // Where the light arrives from, how far, and what leaves it that way.
        const PunctualLight& light = delta[index];
        const DeltaArrival a = delta_arrival(light, si.position);
        if (on_surface(a)) {  // a light exactly on the surface lights nothing
            recorder.delta_light(index, LightOutcome::OnSurface, view, a, nullptr, Vec3{0.0f});
            continue;
        }
        // A light behind the surface (as seen from the viewer's side) adds
        // nothing, unless the material lets light through (a rough thin
        // transmissive pbr): its shadow ray then leaves from the back.
        const bool behind = dot(si.n_g, a.wi) <= 0.0f;
        if (behind && !transmits_diffusely(material)) {
            recorder.delta_light(index, LightOutcome::Behind, view, a, nullptr, Vec3{0.0f});
            continue;
        }
        // Outside a spot's cone nothing leaves the light this way: no shadow ray is needed.
        const float factor = delta_factor(light, a.wi);
        if (!(factor > 0.0f)) {
            recorder.delta_light(index, LightOutcome::OutsideCone, view, a, nullptr, Vec3{0.0f});
            continue;
        }

        // The shadow ray, made only for a light that can contribute.
        const Vec3 origin = behind ? offset_ray_origin(si.position, si.position_error, -si.n_g) : shadow_origin;
        const Ray shadow = delta_shadow_ray(light, a, origin);
        ++counters.shadow_rays;
        const Vec3 transmittance = media != nullptr ? shadow_transmittance(accel, *media, si.n_g, shadow) : Vec3{1.0f};
        if (media != nullptr ? !(max_component(transmittance) > 0.0f) : occluded(accel, shadow)) {
            recorder.delta_light(index, LightOutcome::Blocked, view, a, &shadow, Vec3{0.0f});
            continue;
        }

        // L += I / |c − x|² · f_r(x, ω_i, ω_o) · |n_s · ω_i|   (a spot's I carries s²; a sun's E divided by 1, exactly)
        const Vec3 f_r = eval_bsdf(material, bsdf_point, wo, a.wi);
        Vec3 contribution = beta * (emitted_towards(light, factor) *
                                    (std::fabs(dot(si.n_s, a.wi)) / inverse_square_divisor(light, a)) * f_r);
        if (media != nullptr) contribution = contribution * transmittance;
        radiance += contribution;
        recorder.delta_light(index, LightOutcome::Visible, view, a, &shadow, contribution, transmittance);
    }
}

}  // namespace sombra
