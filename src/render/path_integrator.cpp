// The path integrator of spec §10: L = L_e + ∫ f L_i |n_s·ω_i| dω_i by
// unidirectional path tracing. At each vertex, next-event estimation (every
// point light, plus one sampled emitter or environment point), then a new
// direction from the BSDF. Emitters and the environment are reached by both
// strategies and weighted by the power heuristic, so each is counted once.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "render/bsdf/bsdf.h"
#include "render/delta_lights.h"
#include "render/first_hit.h"
#include "render/integrator.h"
#include "render/interaction.h"
#include "render/media/grid_medium.h"
#include "render/media/homogeneous_medium.h"
#include "render/media/medium_boundary.h"
#include "render/media/phase_function.h"
#include "render/medium_vertex.h"
#include "render/ray_cone.h"
#include "render/sample_recorder.h"
#include "render/shading.h"
#include "render/shadow_ray.h"

namespace sombra {

namespace {

// Russian roulette may end a path only after this many scattering events.
constexpr int kRouletteStart = 3;

// Russian roulette's survival probability for a path of throughput β (with
// refraction's (η_i/η_t)² undone): the cube root of max(β), where the usual
// max(β) ends paths whose later bounces still matter; a survivor's
// throughput β/q = max(β)^(2/3) stays below 1.
float roulette_survival(Vec3 beta, float eta_scale) {
    return std::min(1.0f, std::cbrt(max_component(beta) * eta_scale));
}

// The normal that light selection (the light tree's cosine bound) sees at
// si: n_s, or none (zero) where the BSDF also transmits, so that emitters
// behind the surface keep their chance.
Vec3 light_normal(const Material& m, const SurfaceInteraction& si) {
    return transmits_diffusely(m) ? Vec3{0.0f} : si.n_s;
}

// One sampled emitter or environment direction, MIS-weighted against the
// BSDF's density for the same direction (spec §10's next-event estimation).
template <class Recorder>
Vec3 sample_one_light(const IntegratorContext& ctx, const ShadingView& view, float u_choice, SampleStream::Pair u,
                      RayCounters& counters, Recorder& recorder, const ShadowMedia* media) {
    const SurfaceInteraction& si = view.si;
    LightSample ls;
    if (!sample_light(*ctx.lights, *ctx.scene, si.position, light_normal(view.material, si), u_choice, u.u1, u.u2,
                      ls)) {
        recorder.sampled_light(nullptr, view, nullptr, false, 0.0f, 0.0f, Vec3{0.0f});
        return Vec3{0.0f};
    }
    const Vec3 f = eval_bsdf(view.material, view.bsdf_point, view.wo, ls.wi) * std::fabs(dot(si.n_s, ls.wi));
    if (!(max_component(f) > 0.0f)) {
        recorder.sampled_light(&ls, view, nullptr, false, 0.0f, 0.0f, Vec3{0.0f});
        return Vec3{0.0f};
    }

    const Vec3 origin = spawn_origin(si, ls.wi);
    ++counters.shadow_rays;
    // Toward an emitter the ray stops just short of the sampled point, so
    // that the emitter itself does not count as its own occluder.
    const Ray shadow = ls.at_infinity ? Ray{origin, ls.wi} : Ray{origin, ls.target - origin, 1.0f - 1e-4f};
    const Vec3 transmittance = media != nullptr ? shadow_transmittance(*ctx.accel, *media, si.n_g, shadow) : Vec3{1.0f};
    if (media != nullptr ? !(max_component(transmittance) > 0.0f) : occluded(*ctx.accel, shadow)) {
        recorder.sampled_light(&ls, view, &shadow, true, 0.0f, 0.0f, Vec3{0.0f});
        return Vec3{0.0f};
    }
    const float bsdf_pdf =
        ctx.strategy == LightStrategy::Mis ? pdf_bsdf(view.material, view.bsdf_point, view.wo, ls.wi) : 0.0f;
    const float weight = ctx.strategy == LightStrategy::Mis ? power_heuristic(ls.pdf, bsdf_pdf) : 1.0f;
    Vec3 contribution = f * ls.radiance * (weight / ls.pdf);
    if (media != nullptr) contribution = contribution * transmittance;
    recorder.sampled_light(&ls, view, &shadow, false, bsdf_pdf, weight, contribution, transmittance);
    return contribution;
}

// Tells `recorder` of the first surface a camera ray meets where the path
// may scatter in a medium before it (the denoiser's features).
template <class Recorder>
void record_first_surface(const Scene& scene, const Ray& ray, const Hit& hit, const RayCone& cone, Recorder& recorder,
                          Vec3 beta) {
    SurfaceInteraction first = make_surface_interaction(scene, ray, hit);
    std::optional<Material> first_textured;
    const Material& material =
        needs_resolved_material(scene, first)
            ? resolve_material(scene, first, first_textured.emplace(),
                               surface_footprint(cone, cone.active() ? hit.t * length(ray.dir) : 0.0f, ray.dir,
                                                 first.n_g))
            : scene.materials[first.material];
    recorder.surface(ray, hit, first, material, beta);
}

template <class Recorder>
Vec3 trace_path_recorded(const IntegratorContext& ctx, const Ray& camera_ray, SampleStream& samples,
                         RayCounters& counters, Recorder& recorder) {
    const Scene& scene = *ctx.scene;
    const LightSet& lights = *ctx.lights;
    ++counters.camera_rays;

    Vec3 radiance{0.0f};
    Vec3 beta{1.0f};             // the path's throughput: product of f·|cos|/pdf so far
    float eta_scale = 1.0f;      // undoes refraction's (η_i/η_t)² in beta for Russian roulette
    bool previous_delta = true;  // the camera "vertex" counts as delta: no MIS for what it sees
    float previous_pdf = 0.0f;   // the BSDF's solid-angle density of the last bounce
    Vec3 previous_position{0.0f};
    Vec3 previous_normal{0.0f};  // its shading normal: the light tree's choice depends on both
    Ray ray = camera_ray;
    // The current ray's cone for choosing mip levels (render/ray_cone.h).
    RayCone cone =
        ctx.ray_cones ? camera_ray_cone(ctx.camera_pixel_area, camera_ray.dir, ctx.orthographic_camera) : RayCone{};
    // The hit's material when it has textures (render/shading.h), built on
    // the first hit that needs one, so that untextured paths never copy a
    // whole default Material.
    std::optional<Material> textured;
    // The weight of an emitter or the environment reached by a BSDF-sampled
    // bounce whose density was bsdf_pdf, where next-event estimation would
    // have picked the same direction with light_pdf.
    auto bounce_weight = [&ctx](float bsdf_pdf, float light_pdf) {
        switch (ctx.strategy) {
            case LightStrategy::LightOnly: return light_pdf > 0.0f ? 0.0f : 1.0f;
            case LightStrategy::BsdfOnly: return 1.0f;
            case LightStrategy::Mis: break;
        }
        return power_heuristic(bsdf_pdf, light_pdf);
    };

    // Russian roulette after `events` scattering events (surface and
    // medium), unbiased: survivors are re-weighted by 1/q.
    auto survives_roulette = [&](int events, SampleStream::Slot slot) {
        if (events + 1 <= kRouletteStart) return true;
        const float q = roulette_survival(beta, eta_scale);
        if (q >= 1.0f) return true;
        const float u_roulette = samples.read_1d(slot);
        const bool survived = !(u_roulette >= q);
        if (survived) beta = beta / q;
        recorder.roulette(q, u_roulette, survived, beta);
        if (!survived) recorder.end("Russian roulette ended the path");
        return survived;
    };

    // Which medium the path is in (spec §26; kNoMedium: vacuum), tracked
    // only where the scene has media or interface surfaces.
    const bool tracking = tracks_media(scene);
    std::uint32_t medium = starting_medium(scene);
    // Grid media's tracking draws as many numbers as it needs from here.
    TrackingRng rng{mix64(samples.pixel_key ^ (samples.index + 1ull) * 0xd1b54a32d192ed03ull)};
    int volume_events = 0;
    int crossings = 0;
    for (int depth = 0;;) {
        Hit hit;
        const bool found = intersect(*ctx.accel, ray, hit);
        if (medium != kNoMedium) [[unlikely]] {
            const Medium& m = scene.media[medium];
            // Along the segment to the hit (or without end): the medium's own
            // light, then where, if anywhere, the path scatters in it.
            const float dir_length = length(ray.dir);
            const float end = found ? hit.t * dir_length : std::numeric_limits<float>::infinity();
            if constexpr (Recorder::kWantsFirstSurface) {
                // The denoiser's features describe the surface the camera
                // ray meets, whether or not the path scatters before it.
                if (found && depth + volume_events == 0 && !is_interface(scene, hit.triangle, hit.instance))
                    record_first_surface(scene, ray, hit, cone, recorder, beta);
            }
            const SampleStream::Slot channel_slot = samples.take_1d();
            const SampleStream::Slot distance_slot = samples.take_1d();
            FreeFlight flight;
            Vec3 emitted{0.0f};
            if (m.density) {
                flight = sample_grid_free_flight(m, ray.origin, ray.dir / dir_length, end, rng);
            } else {
                emitted = beta * homogeneous_emission(m, end);
                radiance += emitted;
                flight = sample_homogeneous_free_flight(m, end, samples.read_1d(channel_slot),
                                                        samples.read_1d(distance_slot));
            }
            recorder.segment(medium, flight.scattered ? flight.t : end, flight.scattered, flight.weight, emitted);
            beta = beta * flight.weight;
            if (!(max_component(beta) > 0.0f)) {
                recorder.end("the medium absorbed the path");
                break;
            }
            if (flight.scattered) {
                if (volume_events >= ctx.max_volume_depth) {
                    recorder.end("max_volume_depth scattering events in media reached");
                    break;
                }
                ++volume_events;
                const Vec3 d_in = ray.dir / dir_length;
                const Vec3 x = ray.origin + d_in * flight.t;
                const SampleStream::Slot light_slot = samples.take_2d();
                const SampleStream::Slot choice_slot = samples.take_1d();
                const SampleStream::Slot phase_slot = samples.take_2d();
                const SampleStream::Slot roulette_slot = samples.take_1d();
                const SampleStream::Pair u_light = samples.read_2d(light_slot);
                recorder.medium_event(medium, x, ray, beta);
                radiance += beta * medium_direct_light(ctx, medium, x, d_in, samples.read_1d(choice_slot), u_light.u1,
                                                       u_light.u2, counters, rng, recorder);
                // The phase function is sampled exactly: the throughput is unchanged.
                const SampleStream::Pair u_phase = samples.read_2d(phase_slot);
                const PhaseSample ps = sample_henyey_greenstein(m.g, d_in, u_phase.u1, u_phase.u2);
                recorder.phase_bounce(ps.out, ps.pdf, beta);
                previous_delta = false;
                previous_pdf = ps.pdf;
                previous_position = x;
                previous_normal = Vec3{0.0f};
                ray = Ray{x, ps.out};
                cone = RayCone{};
                ++counters.bounce_rays;
                if (!survives_roulette(depth + volume_events - 1, roulette_slot)) break;
                continue;
            }
        }
        if (found && tracking && is_interface(scene, hit.triangle, hit.instance)) [[unlikely]] {
            // An interface changes the medium and nothing else: the ray goes
            // on from the far side, and the last bounce's MIS data stay.
            if (++crossings > kMaxInterfaceCrossings) {
                recorder.end("more interface crossings than sombra follows");
                break;
            }
            const SurfaceInteraction si = make_surface_interaction(scene, ray, hit);
            medium = medium_sides(scene, si, medium).far;
            recorder.crossed(ray, hit, medium);
            cone = scattered_cone(cone, cone.active() ? hit.t * length(ray.dir) : 0.0f, true);
            ray = Ray{offset_ray_origin(si.position, si.position_error, -si.n_g), ray.dir};
            continue;
        }
        if (!found) {
            const Vec3 dir = normalize(ray.dir);
            const Vec3 le = eval_environment(lights.environment, dir);
            if (max_component(le) > 0.0f) {
                const float light_pdf = previous_delta ? 0.0f : pdf_light_environment(lights, dir);
                const float w = previous_delta ? 1.0f : bounce_weight(previous_pdf, light_pdf);
                radiance += beta * le * w;
                recorder.escaped(ray, beta, le, w, previous_delta ? 0.0f : previous_pdf, light_pdf);
            } else {
                recorder.escaped(ray, beta, le, 1.0f, 0.0f, 0.0f);
            }
            recorder.end(depth + volume_events == 0 ? "the camera ray left the scene" : "the ray left the scene");
            break;
        }

        SurfaceInteraction si = make_surface_interaction(scene, ray, hit);
        const float hit_distance = cone.active() ? hit.t * length(ray.dir) : 0.0f;
        const Material& material = needs_resolved_material(scene, si)
                                       ? resolve_material(scene, si, textured ? *textured : textured.emplace(),
                                                          surface_footprint(cone, hit_distance, ray.dir, si.n_g))
                                       : scene.materials[si.material];
        const Vec3 wo = -normalize(ray.dir);
        const MediumSides sides = tracking ? medium_sides(scene, si, medium) : MediumSides{medium, medium, false};
        // The segment just travelled ran inside the volume that the hit
        // surface bounds (KHR_materials_volume): Beer–Lambert along its
        // length, unless the object's interior medium replaces it.
        if (!si.outside && material.type == MaterialType::Pbr && material.thickness > 0.0f && !sides.boundary)
            beta = beta * volume_transmittance(material, hit.t * length(ray.dir));
        recorder.surface(ray, hit, si, material, beta);

        const Vec3 le = emitted_radiance(material, si);
        if (max_component(le) > 0.0f) {
            const float light_pdf = previous_delta
                                        ? 0.0f
                                        : pdf_light_triangle(lights, scene, si.triangle, si.instance, previous_position,
                                                             previous_normal, si.position);
            const float w = previous_delta ? 1.0f : bounce_weight(previous_pdf, light_pdf);
            radiance += beta * le * w;
            recorder.emission(le, w, previous_delta ? 0.0f : previous_pdf, light_pdf, beta * le * w);
        }
        if (depth >= ctx.max_depth) {
            recorder.end("max_depth scattering events reached");
            break;
        }

        const BsdfPoint bsdf_point = make_bsdf_point(si.n_g, si.n_s, si.outside, si.n_c);
        // Every vertex takes the same dimensions whether it uses them or
        // not, so that dimension k means the same thing on every path; it
        // computes only those it reads.
        const SampleStream::Slot light_slot = samples.take_2d();
        const SampleStream::Slot choice_slot = samples.take_1d();
        const SampleStream::Slot bsdf_slot = samples.take_2d();
        const SampleStream::Slot lobe_slot = samples.take_1d();
        const SampleStream::Slot roulette_slot = samples.take_1d();

        const ShadingView view{si, material, bsdf_point, wo};
        if (!is_delta_bsdf(material)) {
            const ShadowMedia shadow_media{&scene, sides, true, &rng};
            const ShadowMedia* media = tracking ? &shadow_media : nullptr;
            add_delta_lights(lights, *ctx.accel, si, material, bsdf_point, wo, beta, radiance, counters, recorder,
                             media);
            if (lights.has_sampled_lights() && ctx.strategy != LightStrategy::BsdfOnly) {
                const SampleStream::Pair u_light = samples.read_2d(light_slot);
                radiance += beta * sample_one_light(ctx, view, samples.read_1d(choice_slot), u_light, counters,
                                                    recorder, media);
            }
        } else {
            recorder.delta_material();
        }

        BsdfSample bs;
        const SampleStream::Pair u_bsdf = samples.read_2d(bsdf_slot);
        const float u_lobe = uses_lobe_choice(material) ? samples.read_1d(lobe_slot) : 0.0f;
        if (!sample_bsdf(material, bsdf_point, wo, u_lobe, u_bsdf.u1, u_bsdf.u2, bs)) {
            recorder.bounce(nullptr, view, beta);
            recorder.end("the BSDF sampled no direction");
            break;
        }
        beta = beta * bs.weight;
        recorder.bounce(&bs, view, beta);
        if (!(max_component(beta) > 0.0f)) {
            recorder.end("the throughput became zero");
            break;
        }
        if (bs.transmission) eta_scale *= transmission_eta_scale(material, si.outside);
        previous_delta = bs.delta;
        previous_pdf = bs.pdf;
        previous_position = si.position;
        previous_normal = light_normal(material, si);
        ray = Ray{spawn_origin(si, bs.wi), bs.wi};
        medium = medium_toward(sides, si.n_g, bs.wi);
        cone = scattered_cone(cone, hit_distance, bs.delta);
        ++counters.bounce_rays;

        if (!survives_roulette(depth + volume_events, roulette_slot)) break;
        ++depth;
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

Vec3 trace_path(const IntegratorContext& ctx, const Ray& ray, SampleStream& samples, RayCounters& counters) {
    NoRecorder none;
    return trace_path_recorded(ctx, ray, samples, counters, none);
}

Vec3 trace_path(const IntegratorContext& ctx, const Ray& ray, SampleStream& samples, RayCounters& counters,
                SampleRecord& record) {
    SampleRecorder recorder(*ctx.scene, *ctx.lights, *ctx.accel, record);
    record.path = true;
    return trace_path_recorded(ctx, ray, samples, counters, recorder);
}

Vec3 trace_path(const IntegratorContext& ctx, const Ray& ray, SampleStream& samples, RayCounters& counters,
                FirstHit& first) {
    FirstHitRecorder recorder(first);
    return trace_path_recorded(ctx, ray, samples, counters, recorder);
}

}  // namespace sombra
