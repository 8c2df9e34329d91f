// The story as one JSON object. Floats are written as the doubles they
// convert to exactly, so "value" reads back to the very floats the render
// computed.
#include <cmath>
#include <nlohmann/json.hpp>

#include "explain/describe.h"
#include "explain/explain.h"

namespace sombra {

namespace {

using Json = nlohmann::ordered_json;

Json number(float v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";  // JSON has no infinity (an environment light's distance)
    return static_cast<double>(v);
}
Json vec(Vec3 v) { return Json::array({number(v.x), number(v.y), number(v.z)}); }

class JsonStory {
public:
    JsonStory(const ExplainContext& context, const SampleRecord& record) : c_(context), r_(record) {}

    Json build() const {
        const RenderSettings& s = c_.job.settings;
        Json j;
        j["pixel"] = {r_.pixel_x, r_.pixel_y};
        j["sample"] = r_.sample;
        j["value"] = vec(r_.value);
        j["scene"] = c_.scene_file;
        j["width"] = s.width;
        j["height"] = s.height;
        j["spp"] = s.spp;
        j["seed"] = s.seed;
        j["integrator"] = r_.path ? "path" : "direct";
        if (r_.path) j["max_depth"] = s.max_depth;
        j["camera_ray"] = {{"pixel_offset", {number(r_.offset_x), number(r_.offset_y)}},
                           {"s", number(r_.s)},
                           {"t", number(r_.t)},
                           {"origin", vec(r_.origin)},
                           {"direction", vec(r_.direction)}};
        if (c_.job.camera.orthographic) {
            const Camera& cam = c_.job.camera;
            j["camera_ray"]["orthographic"] = {{"half_width", number(length(cam.left))},
                                               {"half_height", number(length(cam.up))}};
        }
        if (r_.lens) {
            const Camera& cam = c_.job.camera;
            j["camera_ray"]["lens"] = {{"sample", {number(r_.lens_u), number(r_.lens_v)}},
                                       {"aperture_radius", number(cam.lens_radius)},
                                       {"focus_distance", number(cam.focus_distance)}};
        }
        const VertexRecord* first = r_.vertices.empty() ? nullptr : &r_.vertices.front();
        j["hit"] = first && first->hit ? hit(first->surface) : Json(nullptr);
        j["lights"] = first ? lights(*first) : Json::array();
        Json vertices = Json::array();
        for (const VertexRecord& v : r_.vertices) vertices.push_back(vertex(v));
        j["vertices"] = vertices;
        j["end"] = r_.end;
        j["nonfinite"] = r_.nonfinite;
        if (c_.denoised) j["denoise"] = denoise(*c_.denoised);
        return j;
    }

private:
    Json where(std::uint32_t triangle, std::uint32_t instance = kNoInstance) const {
        const TriangleOrigin o = triangle_origin(c_.scene, triangle, instance);
        Json j{{"object", o.object}, {"file", o.file}, {"triangle", o.triangle}};
        // In an instance the triangle is its mesh's; "scene_triangle" indexes the world geometry only.
        if (o.instance)
            j["instance"] = *o.instance;
        else
            j["scene_triangle"] = triangle;
        return j;
    }

    // The material's name and type, and its parameters as the BSDF saw them at the hit.
    Json material(const HitRecord& h) const {
        const Material& named = c_.scene.materials[h.material];
        Json j = {{"name", named.name}, {"type", material_type_name(h.shaded.type)}, {"textured", named.textured}};
        for (const MaterialParameter& p : material_parameters(h.shaded)) {
            if (p.value.size() == 3)
                j[p.name] = vec(Vec3{p.value[0], p.value[1], p.value[2]});
            else
                j[p.name] = number(p.value[0]);
        }
        return j;
    }

    Json hit(const HitRecord& h) const {
        Json j = where(h.triangle, h.instance);
        j["t"] = number(h.t);
        j["distance"] = number(h.distance);
        j["barycentric"] = {number(h.b1), number(h.b2)};
        j["x"] = vec(h.position);
        j["n_g"] = vec(h.n_g);
        j["n_s"] = vec(h.n_s);
        if (h.n_c != Vec3{}) j["n_c"] = vec(h.n_c);
        j["outside"] = h.outside;
        if (h.has_uv) j["uv"] = {number(h.uv.x), number(h.uv.y)};
        if (h.uv_footprint > 0.0f) j["uv_footprint"] = number(h.uv_footprint);
        j["material"] = material(h);
        return j;
    }

    // The terms of f_r: the lobes always shown, the total, then the others
    // (a pbr material's transmission, clearcoat, sheen) where they are not 0.
    static Json f_terms(const BsdfTerms& terms, Vec3 f) {
        Json j;
        for (const LobeName& lobe : kLobeNames)
            if (lobe.always_shown) j[lobe.name] = vec(terms.*lobe.term);
        j["total"] = vec(f);
        for (const LobeName& lobe : kLobeNames)
            if (!lobe.always_shown && terms.*lobe.term != Vec3{0.0f}) j[lobe.name] = vec(terms.*lobe.term);
        return j;
    }

    // Cut-outs a ray went through, nearest first.
    Json holes(const std::vector<HoleRecord>& listed) const {
        Json list = Json::array();
        for (const HoleRecord& h : listed) {
            Json hole = where(h.triangle);
            hole["t"] = number(h.t);
            hole["alpha"] = number(h.alpha);
            hole["cutoff"] = number(h.cutoff);
            list.push_back(hole);
        }
        return list;
    }

    Json blocker(const BlockerRecord& b) const {
        // No surface: the media on the way took all the light (spec §26).
        if (b.triangle == kNoTriangle) return {{"object", nullptr}, {"media", true}};
        Json j = where(b.triangle, b.instance);
        j["distance"] = number(b.distance);
        return j;
    }

    Json delta_light(const DeltaLightRecord& l, bool medium_vertex) const {
        const PunctualLight& light = c_.job.lights.delta[l.light];
        const LightTypeTraits type = light_type_traits(light.type);
        Json j = {{"type", type.name}, {"index", l.light}};
        if (type.positioned) j["position"] = vec(light.position);
        if (type.directed) j["direction"] = vec(light.direction);
        j[type.power_key] = vec(light.intensity);
        if (type.coned) {
            j["cos_outer"] = number(light.cos_outer);
            j["cos_inner"] = number(light.cos_inner);
        }
        j["outcome"] = outcome_name(l.outcome);
        if (l.outcome != LightOutcome::OnSurface) {
            j["omega_i"] = vec(l.wi);
            // A light at infinity is unbounded: no distance (spec §16).
            j["distance"] = type.positioned ? number(l.distance) : Json(nullptr);
            j["cos_g"] = number(l.cos_g);
            j["cos_s"] = number(l.cos_s);
            if (type.coned) j["spot_factor"] = number(l.spot_factor);
            j["incident"] = vec(l.incident);
            if (medium_vertex)
                j["phase"] = number(l.f.x);
            else
                j["f_r"] = f_terms(l.f_terms, l.f);
            j["transmittance"] = vec(l.transmittance);
        }
        if (l.outcome == LightOutcome::Blocked) j["blocker"] = blocker(l.blocker);
        if (l.outcome == LightOutcome::Visible) {
            j["holes"] = holes(l.holes);
            j["holes_crossed"] = l.holes_crossed;
        }
        j["contribution"] = vec(l.contribution);
        return j;
    }

    Json sampled_light(const SampledLightRecord& l, bool medium_vertex) const {
        if (!l.sampled) return {{"type", "sampled"}, {"outcome", "none"}, {"contribution", vec(l.contribution)}};
        Json j = {{"type", l.environment ? "environment" : "emitter"}, {"light", l.light}};
        if (!l.environment) {
            j["emitter"] = where(l.triangle, l.instance);
            j["point"] = vec(l.target);
        }
        j["outcome"] = outcome_name(l.outcome);
        j["omega_i"] = vec(l.wi);
        j["distance"] = number(l.distance);
        j["radiance"] = vec(l.radiance);
        j["light_pdf"] = number(l.light_pdf);
        j[medium_vertex ? "phase_pdf" : "bsdf_pdf"] = number(l.bsdf_pdf);
        j["mis_weight"] = number(l.mis_weight);
        if (!medium_vertex) j["cos_s"] = number(l.cos_s);
        if (!l.environment) j["cos_light"] = number(l.cos_light);
        if (medium_vertex)
            j["phase"] = number(l.f.x);
        else
            j["f_r"] = f_terms(l.f_terms, l.f);
        j["transmittance"] = vec(l.transmittance);
        if (l.outcome == LightOutcome::Blocked) j["blocker"] = blocker(l.blocker);
        if (l.outcome == LightOutcome::Visible) {
            j["holes"] = holes(l.holes);
            j["holes_crossed"] = l.holes_crossed;
        }
        j["contribution"] = vec(l.contribution);
        return j;
    }

    Json lights(const VertexRecord& v) const {
        Json list = Json::array();
        for (const DeltaLightRecord& l : v.delta_lights) list.push_back(delta_light(l, v.medium_event));
        if (r_.path && (v.hit || v.medium_event) && !v.delta_material && c_.job.lights.has_sampled_lights())
            list.push_back(sampled_light(v.sampled_light, v.medium_event));
        return list;
    }

    // Spec §26: the media the arriving ray went through and the interfaces it crossed.
    Json media(const VertexRecord& v) const {
        Json segments = Json::array();
        for (const MediumSegmentRecord& m : v.segments)
            segments.push_back({{"medium", c_.scene.media[m.medium].name},
                                {"distance", std::isfinite(m.distance) ? number(m.distance) : Json(nullptr)},
                                {"scattered", m.scattered},
                                {"weight", vec(m.weight)},
                                {"emission", vec(m.emission)}});
        Json crossings = Json::array();
        for (const CrossingRecord& c : v.crossings) {
            Json j = where(c.triangle, c.instance);
            j["distance"] = number(c.distance);
            j["medium_after"] = c.medium_after == kNoMedium ? Json(nullptr) : Json(c_.scene.media[c.medium_after].name);
            j["after_segments"] = c.after_segments;
            crossings.push_back(j);
        }
        return {{"segments", segments}, {"interfaces", crossings}};
    }

    static Json emission(const EmissionRecord& e) {
        return {{"radiance", vec(e.radiance)},
                {"mis_weight", number(e.mis_weight)},
                {"bsdf_pdf", number(e.bsdf_pdf)},
                {"light_pdf", number(e.light_pdf)},
                {"contribution", vec(e.contribution)}};
    }

    Json vertex(const VertexRecord& v) const {
        Json j = {{"depth", v.depth},
                  {"ray", {{"origin", vec(v.ray_origin)}, {"direction", vec(v.ray_dir)}}},
                  {"throughput", vec(v.throughput)}};
        j["hit"] = v.hit ? hit(v.surface) : Json(nullptr);
        j["holes"] = holes(v.holes);
        j["holes_crossed"] = v.holes_crossed;
        if (!v.segments.empty() || !v.crossings.empty()) j["media"] = media(v);
        if (v.medium_event) {
            j["scatter"] = {{"medium", c_.scene.media[v.medium].name},
                            {"x", vec(v.position)},
                            {"g", number(c_.scene.media[v.medium].g)}};
        } else {
            j["emission"] = emission(v.emission);
        }
        if (!v.hit && !v.medium_event) return j;
        j["delta_material"] = v.delta_material;
        j["lights"] = lights(v);
        const BounceRecord& b = v.bounce;
        if (r_.path && b.sampled) {
            Json bounce = {{"omega_i", vec(b.wi)},           {"f_r", vec(b.f)},
                           {"pdf", number(b.pdf)},           {"delta", b.delta},
                           {"transmission", b.transmission}, {"weight", vec(b.weight)},
                           {"throughput", vec(b.throughput)}};
            if (b.roulette)
                bounce["roulette"] = {{"q", number(b.roulette_q)},
                                      {"u", number(b.roulette_u)},
                                      {"survived", b.survived},
                                      {"throughput", vec(b.throughput_after)}};
            j["bounce"] = bounce;
        }
        return j;
    }

    static Json rgb(const std::array<float, 3>& v) { return Json::array({number(v[0]), number(v[1]), number(v[2])}); }

    // Spec §25: the pixel denoised, as rendered, and every term with a
    // nonzero weight; the weights are doubles, written to read back exactly.
    static Json denoise(const DenoiseStory& d) {
        Json weights = Json::array();
        for (const DenoiseTerm& t : d.pixel.terms)
            weights.push_back({{"pixel", Json::array({t.x, t.y})},
                               {"half", t.half == 0 ? "a" : "b"},
                               {"w", Json::array({t.weight[0], t.weight[1], t.weight[2]})},
                               {"raw", rgb(t.raw)}});
        const std::array<bool, 3>& clamped = d.pixel.clamped;
        return {{"value", rgb(d.pixel.value)},
                {"raw", rgb(d.raw)},
                {"clamped", Json::array({clamped[0], clamped[1], clamped[2]})},
                {"weights", weights}};
    }

    const ExplainContext& c_;
    const SampleRecord& r_;
};

}  // namespace

std::string explain_json(const ExplainContext& context, const SampleRecord& record) {
    return JsonStory(context, record).build().dump(2) + "\n";
}

}  // namespace sombra
