// The two recorders the integrators are compiled with (render/sample_record.h):
// NoRecorder for rendering, whose hooks are empty so that the render loop
// is the same machine code as without them, and SampleRecorder for
// `sombra explain`, which writes each hook's numbers into a SampleRecord.
// Hooks only look: they never change a value the integrator computes, so a
// recorded sample's value is the rendered one, bit for bit.
#pragma once

#include "accel/accel.h"
#include "core/ray.h"
#include "render/bsdf/bsdf.h"
#include "render/interaction.h"
#include "render/lights/delta_arrival.h"
#include "render/lights/lights.h"
#include "render/sample_record.h"
#include "render/shading_view.h"
#include "scene/scene.h"

namespace sombra {

// Records nothing; every hook compiles to nothing.
struct NoRecorder {
    // True for a recorder that wants the camera ray's first surface even
    // where the path scatters in a medium before reaching it (FirstHitRecorder).
    static constexpr bool kWantsFirstSurface = false;
    template <class... Args>
    void escaped(const Args&...) {}
    template <class... Args>
    void surface(const Args&...) {}
    template <class... Args>
    void emission(const Args&...) {}
    template <class... Args>
    void delta_material(const Args&...) {}
    template <class... Args>
    void delta_light(const Args&...) {}
    template <class... Args>
    void sampled_light(const Args&...) {}
    template <class... Args>
    void bounce(const Args&...) {}
    template <class... Args>
    void roulette(const Args&...) {}
    template <class... Args>
    void end(const Args&...) {}
    template <class... Args>
    void value(const Args&...) {}
    template <class... Args>
    void segment(const Args&...) {}
    template <class... Args>
    void crossed(const Args&...) {}
    template <class... Args>
    void medium_event(const Args&...) {}
    template <class... Args>
    void medium_delta_light(const Args&...) {}
    template <class... Args>
    void medium_sampled_light(const Args&...) {}
    template <class... Args>
    void phase_bounce(const Args&...) {}
};

// Fills a SampleRecord. The recorder also looks up what blocked a shadow ray
// (a closest-hit query of its own), which the integrator never needs.
class SampleRecorder {
public:
    static constexpr bool kWantsFirstSurface = false;
    SampleRecorder(const Scene& scene, const LightSet& lights, const Accel& accel, SampleRecord& record)
        : scene_(scene), lights_(lights), accel_(accel), record_(record) {}

    // The ray left the scene: le is what the environment (or background)
    // sends back, weighted by w against next-event estimation.
    void escaped(const Ray& ray, Vec3 beta, Vec3 le, float w, float bsdf_pdf, float light_pdf);
    // The ray hit `hit`, carrying throughput beta; `material` is the material resolved there.
    void surface(const Ray& ray, const Hit& hit, const SurfaceInteraction& si, const Material& material, Vec3 beta);
    void emission(Vec3 le, float w, float bsdf_pdf, float light_pdf, Vec3 contribution);
    void delta_material();
    // One delta light's term; `shadow` is the shadow ray traced (Blocked,
    // Visible), else null; distance_squared is +∞ for a directional light.
    void delta_light(std::uint32_t light, LightOutcome outcome, const ShadingView& view, const DeltaArrival& arrival,
                     const Ray* shadow, Vec3 contribution, Vec3 transmittance = Vec3{1.0f});
    // Next-event estimation of one sampled emitter or environment point: `ls`
    // null when nothing was sampled; `shadow` null when no ray was traced.
    void sampled_light(const LightSample* ls, const ShadingView& view, const Ray* shadow, bool blocked, float bsdf_pdf,
                       float w, Vec3 contribution, Vec3 transmittance = Vec3{1.0f});
    // The BSDF's sample (null when it produced none) and the throughput after it.
    void bounce(const BsdfSample* bs, const ShadingView& view, Vec3 beta);
    void roulette(float q, float u, bool survived, Vec3 beta);
    void end(const char* why);
    void value(Vec3 value, bool nonfinite);

    // Spec §26. The ray travelled `distance` through medium `medium`, its
    // throughput multiplied by `weight`, the medium's light `emission`
    // (with β) added; it scattered at the end when `scattered`.
    void segment(std::uint32_t medium, float distance, bool scattered, Vec3 weight, Vec3 emission);
    // The ray crossed the interface surface `hit` into `medium_after`.
    void crossed(const Ray& ray, const Hit& hit, std::uint32_t medium_after);
    // The path scattered in `medium` at x, arriving along `ray` with throughput beta: a new vertex.
    void medium_event(std::uint32_t medium, Vec3 x, const Ray& ray, Vec3 beta);
    // Next-event estimation at the medium vertex: `phase` is the phase
    // function's value toward the light; contributions are without β.
    void medium_delta_light(std::uint32_t light, LightOutcome outcome, const DeltaArrival& arrival, float phase,
                            const Ray* shadow, Vec3 transmittance, Vec3 contribution);
    void medium_sampled_light(const LightSample* ls, Vec3 x, float phase, const Ray* shadow, Vec3 transmittance,
                              float w, Vec3 contribution);
    // The phase function's sample: direction and density (= its value).
    void phase_bounce(Vec3 wi, float pdf, Vec3 beta);

private:
    // Gives `v` the segments and crossings heard since the last vertex.
    void attach_pending(VertexRecord& v);
    VertexRecord& vertex();  // the current vertex (one is made if none exists yet)
    BlockerRecord find_blocker(const Ray& shadow) const;
    // The cut-out crossings of `ray` before t_end, nearest first, at most
    // kMaxHolesListed into `holes` and all counted in `crossed` (a pass over
    // every triangle: the integrator's queries skip holes without a trace).
    void find_holes(const Ray& ray, float t_end, std::vector<HoleRecord>& holes, std::size_t& crossed) const;

    const Scene& scene_;
    const LightSet& lights_;
    const Accel& accel_;
    SampleRecord& record_;
    std::vector<MediumSegmentRecord> pending_segments_;
    std::vector<CrossingRecord> pending_crossings_;
};

}  // namespace sombra
