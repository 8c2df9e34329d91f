#include "render/delta_lights.h"

#include <cmath>
#include <limits>

#include "render/first_hit.h"
#include "render/sample_recorder.h"
#include "render/shading_view.h"

namespace sombra {

template <class Recorder>
void add_delta_lights(const LightSet& lights, const Accel& accel, const SurfaceInteraction& si,
                      const Material& material, const BsdfPoint& bsdf_point, Vec3 wo, Vec3 beta, Vec3& radiance,
                      RayCounters& counters, Recorder& recorder) {
    const ShadingView view{si, material, bsdf_point, wo};
    const Vec3 shadow_origin = offset_ray_origin(si.position, si.position_error, si.n_g);
    constexpr float kUnbounded = std::numeric_limits<float>::infinity();
    for (std::uint32_t index = 0; index < lights.delta.size(); ++index) {
        const PunctualLight& light = lights.delta[index];
        // Where the light arrives from: ω_i, the squared distance (+∞ for a
        // directional light, as the recorder reports it), the inverse-square
        // divisor (1 for a directional light: E has no falloff) and the
        // shadow ray.
        Vec3 wi;
        float distance_squared = kUnbounded, divisor = 1.0f;
        Ray shadow{shadow_origin, Vec3{0.0f}};
        if (light.type == LightType::Directional) {
            // From infinitely far: the light arrives along `direction`
            // everywhere, and the shadow ray has no end.
            wi = -light.direction;
            shadow.dir = wi;
        } else {
            const Vec3 to_light = light.position - si.position;
            distance_squared = dot(to_light, to_light);
            if (!(distance_squared > 0.0f)) {  // a light exactly on the surface lights nothing
                recorder.delta_light(index, LightOutcome::OnSurface, view, Vec3{0.0f}, 0.0f, nullptr, Vec3{0.0f});
                continue;
            }
            wi = to_light / std::sqrt(distance_squared);
            divisor = distance_squared;
            // From the offset origin to the light: t = 1 reaches the light,
            // and the bound just short of it keeps the light's own position
            // (possibly on a surface) from counting as an occluder.
            shadow = Ray{shadow_origin, light.position - shadow_origin, 1.0f - 1e-5f};
        }
        // A light behind the surface (as seen from the viewer's side) adds nothing.
        if (dot(si.n_g, wi) <= 0.0f) {
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

template void add_delta_lights<NoRecorder>(const LightSet&, const Accel&, const SurfaceInteraction&, const Material&,
                                           const BsdfPoint&, Vec3, Vec3, Vec3&, RayCounters&, NoRecorder&);
template void add_delta_lights<SampleRecorder>(const LightSet&, const Accel&, const SurfaceInteraction&,
                                               const Material&, const BsdfPoint&, Vec3, Vec3, Vec3&, RayCounters&,
                                               SampleRecorder&);
template void add_delta_lights<FirstHitRecorder>(const LightSet&, const Accel&, const SurfaceInteraction&,
                                                 const Material&, const BsdfPoint&, Vec3, Vec3, Vec3&, RayCounters&,
                                                 FirstHitRecorder&);

}  // namespace sombra
