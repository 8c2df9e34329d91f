#include "render/sample_recorder.h"

#include "render/lights/delta_light_types.h"
#include "render/shadow_ray.h"

#include "accel/triangle.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sombra {

namespace {

// What a light sample says of itself, seen from x (a surface or medium vertex).
void copy_light_sample(const LightSample& ls, Vec3 x, SampledLightRecord& r) {
    r.environment = ls.at_infinity;
    r.light = ls.light;
    r.triangle = ls.triangle;
    r.instance = ls.instance;
    r.wi = ls.wi;
    r.target = ls.target;
    r.distance = ls.at_infinity ? std::numeric_limits<float>::infinity() : length(ls.target - x);
    r.radiance = ls.radiance;
    r.light_pdf = ls.pdf;
}

}  // namespace

VertexRecord& SampleRecorder::vertex() {
    if (record_.vertices.empty()) record_.vertices.emplace_back();
    return record_.vertices.back();
}

BlockerRecord SampleRecorder::find_blocker(const Ray& shadow) const {
    // The integrator asked only "is anything in the way" (any hit); a learner
    // wants the first thing in the way, so the recorder asks again. Interface
    // surfaces block nothing; with none found, media took all the light.
    Hit hit;
    BlockerRecord blocker;
    if (intersect_past_interfaces(accel_, scene_, shadow, hit)) {
        blocker.triangle = hit.triangle;
        blocker.instance = hit.instance;
        blocker.distance = hit.t * length(shadow.dir);
    }
    return blocker;
}

void SampleRecorder::find_holes(const Ray& ray, float t_end, std::vector<HoleRecord>& holes,
                                std::size_t& crossed) const {
    holes.clear();
    crossed = 0;
    const Cutouts& cutouts = accel_.cutouts;
    if (!cutouts.active()) return;
    const TriangleMesh& mesh = *cutouts.mesh;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const auto triangle = static_cast<std::uint32_t>(i);
        const Material& m = (*cutouts.materials)[mesh.material_ids[i]];
        if (!m.textures.alpha_test) continue;
        float t, b1, b2;
        if (!intersect_triangle(ray.origin, ray.dir, prepare_triangle(mesh, mesh.triangles[i]), t_end, t, b1, b2))
            continue;
        const float alpha = surface_alpha(cutouts, m, triangle, b1, b2);
        if (cut_out_at(m, alpha)) holes.push_back({triangle, t, alpha, m.textures.alpha_cutoff});
    }
    std::sort(holes.begin(), holes.end(), [](const HoleRecord& a, const HoleRecord& b) { return a.t < b.t; });
    crossed = holes.size();
    if (holes.size() > kMaxHolesListed) holes.resize(kMaxHolesListed);
}

void SampleRecorder::escaped(const Ray& ray, Vec3 beta, Vec3 le, float w, float bsdf_pdf, float light_pdf) {
    VertexRecord v;
    v.depth = static_cast<int>(record_.vertices.size());
    v.ray_origin = ray.origin;
    v.ray_dir = normalize(ray.dir);
    v.hit = false;
    find_holes(ray, ray.tmax, v.holes, v.holes_crossed);
    v.throughput = beta;
    v.emission = EmissionRecord{max_component(le) > 0.0f, le, w, bsdf_pdf, light_pdf, beta * le * w};
    attach_pending(v);
    record_.vertices.push_back(v);
}

void SampleRecorder::surface(const Ray& ray, const Hit& hit, const SurfaceInteraction& si, const Material& material,
                             Vec3 beta) {
    VertexRecord v;
    v.depth = static_cast<int>(record_.vertices.size());
    v.ray_origin = ray.origin;
    v.ray_dir = normalize(ray.dir);
    v.hit = true;
    v.surface.triangle = si.triangle;
    v.surface.instance = si.instance;
    v.surface.material = si.material;
    v.surface.t = hit.t;
    v.surface.distance = length(si.position - ray.origin);
    v.surface.b1 = hit.b1;
    v.surface.b2 = hit.b2;
    v.surface.position = si.position;
    v.surface.n_g = si.n_g;
    v.surface.n_s = si.n_s;
    v.surface.n_c = si.n_c;
    v.surface.outside = si.outside;
    v.surface.uv = si.uv;
    v.surface.has_uv = si.has_uv;
    v.surface.uv_footprint = si.uv_footprint;
    v.surface.shaded = material;
    find_holes(ray, hit.t, v.holes, v.holes_crossed);
    v.throughput = beta;
    attach_pending(v);
    record_.vertices.push_back(v);
}

void SampleRecorder::emission(Vec3 le, float w, float bsdf_pdf, float light_pdf, Vec3 contribution) {
    vertex().emission = EmissionRecord{max_component(le) > 0.0f, le, w, bsdf_pdf, light_pdf, contribution};
}

void SampleRecorder::delta_material() { vertex().delta_material = true; }

void SampleRecorder::delta_light(std::uint32_t light, LightOutcome outcome, const ShadingView& view,
                                 const DeltaArrival& arrival, const Ray* shadow, Vec3 contribution,
                                 Vec3 transmittance) {
    DeltaLightRecord r;
    r.transmittance = transmittance;
    r.light = light;
    r.outcome = outcome;
    const Vec3 wi = arrival.wi;
    r.wi = wi;
    r.distance = std::sqrt(arrival.distance_squared);
    r.cos_g = dot(view.si.n_g, wi);
    r.cos_s = std::fabs(dot(view.si.n_s, wi));
    if (outcome != LightOutcome::OnSurface) {
        const PunctualLight& l = lights_.delta[light];
        r.spot_factor = delta_factor(l, wi);
        r.incident = incident_radiance_factor(l, arrival, r.spot_factor);
        r.f_terms = eval_bsdf_terms(view.material, view.bsdf_point, view.wo, wi);
        r.f = eval_bsdf(view.material, view.bsdf_point, view.wo, wi);
    }
    if (outcome == LightOutcome::Blocked && shadow) r.blocker = find_blocker(*shadow);
    if (outcome == LightOutcome::Visible && shadow) find_holes(*shadow, shadow->tmax, r.holes, r.holes_crossed);
    r.contribution = contribution;
    vertex().delta_lights.push_back(r);
}

void SampleRecorder::sampled_light(const LightSample* ls, const ShadingView& view, const Ray* shadow, bool blocked,
                                   float bsdf_pdf, float w, Vec3 contribution, Vec3 transmittance) {
    SampledLightRecord r;
    r.transmittance = transmittance;
    r.sampled = ls != nullptr;
    if (ls) {
        copy_light_sample(*ls, view.si.position, r);
        r.cos_s = std::fabs(dot(view.si.n_s, ls->wi));
        if (!ls->at_infinity && (ls->instance == kNoInstance || ls->instance < scene_.instances.size()) &&
            ls->triangle < surface_mesh(scene_, ls->instance).triangles.size()) {
            const auto [p0, p1, p2] = world_triangle_corners(scene_, ls->triangle, ls->instance);
            r.cos_light = std::fabs(dot(normalize(cross(p1 - p0, p2 - p0)), ls->wi));
        }
        r.f_terms = eval_bsdf_terms(view.material, view.bsdf_point, view.wo, ls->wi);
        r.f = eval_bsdf(view.material, view.bsdf_point, view.wo, ls->wi);
        // Shown for blocked and zero-f samples too: what MIS would have weighed.
        r.bsdf_pdf = shadow && !blocked ? bsdf_pdf : pdf_bsdf(view.material, view.bsdf_point, view.wo, ls->wi);
        r.mis_weight = w;
        // Without a shadow ray the BSDF was 0 there: the light is behind the surface, or the lobe sends nothing its way.
        r.outcome = blocked                                       ? LightOutcome::Blocked
                    : !shadow && dot(view.si.n_g, ls->wi) <= 0.0f ? LightOutcome::Behind
                                                                  : LightOutcome::Visible;
        if (blocked && shadow) r.blocker = find_blocker(*shadow);
        if (!blocked && shadow) find_holes(*shadow, shadow->tmax, r.holes, r.holes_crossed);
    }
    r.contribution = vertex().throughput * contribution;
    vertex().sampled_light = r;
}

void SampleRecorder::bounce(const BsdfSample* bs, const ShadingView& view, Vec3 beta) {
    BounceRecord& b = vertex().bounce;
    b.sampled = bs != nullptr;
    if (bs) {
        b.wi = bs->wi;
        b.f = bs->delta ? Vec3{0.0f} : eval_bsdf(view.material, view.bsdf_point, view.wo, bs->wi);
        b.pdf = bs->pdf;
        b.delta = bs->delta;
        b.transmission = bs->transmission;
        b.weight = bs->weight;
    }
    b.throughput = beta;
    b.throughput_after = beta;
}

void SampleRecorder::roulette(float q, float u, bool survived, Vec3 beta) {
    BounceRecord& b = vertex().bounce;
    b.roulette = true;
    b.roulette_q = q;
    b.roulette_u = u;
    b.survived = survived;
    b.throughput_after = beta;
}

void SampleRecorder::end(const char* why) { record_.end = why; }

void SampleRecorder::attach_pending(VertexRecord& v) {
    v.segments = std::move(pending_segments_);
    v.crossings = std::move(pending_crossings_);
    pending_segments_.clear();
    pending_crossings_.clear();
}

void SampleRecorder::segment(std::uint32_t medium, float distance, bool scattered, Vec3 weight, Vec3 emission) {
    pending_segments_.push_back({medium, distance, scattered, weight, emission});
}

void SampleRecorder::crossed(const Ray& ray, const Hit& hit, std::uint32_t medium_after) {
    pending_crossings_.push_back(
        {hit.triangle, hit.instance, hit.t * length(ray.dir), medium_after, pending_segments_.size()});
}

void SampleRecorder::medium_event(std::uint32_t medium, Vec3 x, const Ray& ray, Vec3 beta) {
    VertexRecord v;
    v.depth = static_cast<int>(record_.vertices.size());
    v.ray_origin = ray.origin;
    v.ray_dir = normalize(ray.dir);
    v.medium_event = true;
    v.medium = medium;
    v.position = x;
    v.throughput = beta;
    attach_pending(v);
    record_.vertices.push_back(v);
}

void SampleRecorder::medium_delta_light(std::uint32_t light, LightOutcome outcome, const DeltaArrival& arrival,
                                        float phase, const Ray* shadow, Vec3 transmittance, Vec3 contribution) {
    DeltaLightRecord r;
    r.light = light;
    r.outcome = outcome;
    r.wi = arrival.wi;
    r.distance = std::sqrt(arrival.distance_squared);
    r.cos_g = 1;
    r.cos_s = 1;
    if (outcome != LightOutcome::OnSurface) {
        const PunctualLight& l = lights_.delta[light];
        r.spot_factor = delta_factor(l, arrival.wi);
        r.incident = incident_radiance_factor(l, arrival, r.spot_factor);
    }
    r.f = Vec3{phase};
    if (outcome == LightOutcome::Blocked && shadow) r.blocker = find_blocker(*shadow);
    r.transmittance = transmittance;
    r.contribution = vertex().throughput * contribution;
    vertex().delta_lights.push_back(r);
}

void SampleRecorder::medium_sampled_light(const LightSample* ls, Vec3 x, float phase, const Ray* shadow,
                                          Vec3 transmittance, float w, Vec3 contribution) {
    SampledLightRecord r;
    r.sampled = ls != nullptr;
    if (ls) {
        copy_light_sample(*ls, x, r);
        r.cos_s = 1;
        r.f = Vec3{phase};
        r.bsdf_pdf = phase;  // the phase function samples itself exactly
        r.mis_weight = w;
        const bool blocked = !(max_component(transmittance) > 0.0f);
        r.outcome = blocked ? LightOutcome::Blocked : LightOutcome::Visible;
        if (blocked && shadow) r.blocker = find_blocker(*shadow);
        r.transmittance = transmittance;
    }
    r.contribution = vertex().throughput * contribution;
    vertex().sampled_light = r;
}

void SampleRecorder::phase_bounce(Vec3 wi, float pdf, Vec3 beta) {
    BounceRecord& b = vertex().bounce;
    b.sampled = true;
    b.wi = wi;
    b.f = Vec3{pdf};
    b.pdf = pdf;
    b.weight = Vec3{1.0f};
    b.throughput = beta;
    b.throughput_after = beta;
}

void SampleRecorder::value(Vec3 value, bool nonfinite) {
    record_.value = value;
    record_.nonfinite = nonfinite;
}

}  // namespace sombra
