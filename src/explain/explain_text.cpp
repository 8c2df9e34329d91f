// The story as text: written for a student who has just read the
// assignment, so each number comes with the name of the term it is.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "explain/describe.h"
#include "explain/explain.h"
#include "explain/explain_denoise.h"
#include "render/lights/delta_light_types.h"

namespace sombra {

namespace {

// The width of the factor names' column ("f_r        = ..."), in characters.
constexpr std::size_t kFactorColumn = 11;

// Characters (code points) of UTF-8 text, as a terminal lays them out.
std::size_t characters(const std::string& text) {
    std::size_t n = 0;
    for (const char c : text) n += (static_cast<unsigned char>(c) & 0xC0u) != 0x80u ? 1 : 0;
    return n;
}

// "diffuse D + lobe L + transmission T": f_r's lobes, those that are shown
// only where they are not 0 (a pbr material's transmission, coat, sheen) left out when they are.
std::string lobe_sum(const BsdfTerms& terms) {
    std::string s;
    for (const LobeName& lobe : kLobeNames)
        if (lobe.always_shown || terms.*lobe.term != Vec3{0.0f})
            s += (s.empty() ? "" : " + ") + std::string(lobe.name) + " " + readable(terms.*lobe.term);
    return s;
}

class Story {
public:
    Story(const ExplainContext& context, const SampleRecord& record) : c_(context), r_(record) {}

    std::string tell() {
        header();
        camera_ray();
        for (const VertexRecord& v : r_.vertices) vertex(v);
        total();
        if (c_.denoised) out_ << denoise_text(*c_.denoised, r_.pixel_x, r_.pixel_y);
        return out_.str();
    }

private:
    void header() {
        const RenderSettings& s = c_.job.settings;
        out_ << "Pixel (" << r_.pixel_x << ", " << r_.pixel_y << "), sample " << r_.sample << " of " << s.spp << ", of "
             << c_.scene_file << " at " << s.width << "x" << s.height << ", "
             << (r_.path ? "path integrator, max_depth " + std::to_string(s.max_depth)
                         : std::string("direct integrator"))
             << ", seed " << s.seed << "\n";
    }

    void camera_ray() {
        const Camera& cam = c_.job.camera;
        out_ << "\nCamera ray\n";
        out_ << "  position in the pixel  (" << readable(r_.offset_x) << ", " << readable(r_.offset_y) << ")"
             << (c_.job.settings.spp == 1 ? "  (the centre: one sample per pixel)" : "") << "\n";
        out_ << "  image plane            s = " << readable(r_.s) << ", t = " << readable(r_.t)
             << "  (s = 1 − 2(i + x)/W, t = 1 − 2(j + y)/H)\n";
        if (cam.orthographic) {
            // Spec §24: parallel rays from the camera's plane, along f.
            out_ << "  origin                 o + s·l + t·u = " << readable(r_.origin)
                 << "  (orthographic, o = " << readable(cam.origin) << ")\n";
            out_ << "  direction d            f = " << readable(r_.direction) << "\n";
            out_ << "      with l = " << readable(cam.left) << ", u = " << readable(cam.up)
                 << " (the view's half-width " << readable(length(cam.left)) << " and half-height "
                 << readable(length(cam.up)) << ")\n";
            return;
        }
        if (!r_.lens) {
            out_ << "  origin o               " << readable(r_.origin) << "\n";
            out_ << "  direction d            s·l + t·u + f = " << readable(r_.direction) << "\n";
            out_ << "      with l = " << readable(cam.left) << ", u = " << readable(cam.up)
                 << ", f = " << readable(cam.forward) << "\n";
            return;
        }
        // A thin lens (spec §17): the ray leaves a point of the lens and aims
        // where the pinhole ray meets the focus plane.
        out_ << "  lens sample            (" << readable(r_.lens_u) << ", " << readable(r_.lens_v)
             << ") on the unit square, mapped to the disc of radius r = " << readable(cam.lens_radius) << "\n";
        out_ << "  origin                 " << readable(r_.origin)
             << "  (o + r·(x·l̂ + y·û), o = " << readable(cam.origin) << ")\n";
        out_ << "  direction              " << readable(r_.direction)
             << "  (towards where s·l + t·u + f meets the focus plane at distance " << readable(cam.focus_distance)
             << ")\n";
        out_ << "      with l = " << readable(cam.left) << ", u = " << readable(cam.up)
             << ", f = " << readable(cam.forward) << "\n";
    }

    std::string where(std::uint32_t triangle, std::uint32_t instance = kNoInstance) const {
        const TriangleOrigin o = triangle_origin(c_.scene, triangle, instance);
        std::string s = o.object;
        if (!o.file.empty()) s += " (" + o.file + ")";
        return s + instance_words(o) + ", triangle " + std::to_string(o.triangle) + ", material \"" + o.material + "\"";
    }

    // The material's name and type, and its parameters as the BSDF saw them at the hit.
    static std::string material_text(const HitRecord& h, const Material& named) {
        const Material& m = h.shaded;
        std::string s = "\"" + named.name + "\": " + material_type_name(m.type);
        for (const MaterialParameter& p : material_parameters(m)) {
            s += ", " + p.name + " = ";
            s += p.value.size() == 3 ? readable(Vec3{p.value[0], p.value[1], p.value[2]}) : readable(p.value[0]);
        }
        if (named.textured)
            s += "\n           (textured: the values at this hit's uv " + readable(h.uv.x) + ", " + readable(h.uv.y) +
                 (h.uv_footprint > 0.0f ? ", mip-mapped over a footprint " + readable(h.uv_footprint) + " wide in uv"
                                        : "") +
                 "; n_s after its normal or bump map)";
        return s;
    }

    void vertex(const VertexRecord& v) {
        const bool first = v.depth == 0;
        if (r_.path) {
            out_ << "\nVertex " << v.depth
                 << (v.medium_event ? " (a scattering event in a medium)"
                     : first        ? " (what the camera ray meets)"
                                    : "")
                 << "\n";
            if (!first)
                out_ << "  ray      from " << readable(v.ray_origin) << " along " << readable(v.ray_dir) << "\n";
            out_ << "  throughput β = " << readable(v.throughput)
                 << (first ? "" : "  (the product of f·|cos|/pdf of the bounces so far)") << "\n";
        } else {
            out_ << "\nHit\n";
        }
        holes(v.holes, v.holes_crossed, "  through  ", "           ");
        media(v);
        if (v.medium_event) {
            medium_event(v);
            return;
        }
        if (!v.hit) {
            out_ << "  nothing: the ray leaves the scene and sees the "
                 << (c_.scene.environment ? "environment map" : "background") << "\n";
            emission(v.emission, "environment");
            return;
        }
        const HitRecord& h = v.surface;
        out_ << "  object   " << where(h.triangle, h.instance) << "\n";
        out_ << "  t        " << readable(h.t) << " (distance " << readable(h.distance) << ")\n";
        out_ << "  x        " << readable(h.position) << "\n";
        out_ << "  n_g      " << readable(h.n_g) << "  (geometric normal, turned to face the ray)\n";
        const MaterialTextures& maps = c_.scene.materials[h.material].textures;
        // As resolve_material decides (render/shading.cpp): a map on uv set 0
        // needs the hit's uv, one on another set (glTF texCoord) its own.
        const TextureRef& map = maps.normal_map.is_set() ? maps.normal_map : maps.bump_map;
        Vec2 map_uv;
        const bool mapped =
            map.is_set() && (map.uv_set == 0 ? h.has_uv
                                             : interpolate_uv_set(surface_mesh(c_.scene, h.instance), map.uv_set,
                                                                  h.triangle, h.b1, h.b2, map_uv));
        const bool smooth = has_vertex_normals(surface_mesh(c_.scene, h.instance), h.triangle);
        out_ << "  n_s      " << readable(h.n_s)
             << (mapped           ? "  (shading normal: after the material's normal or bump map)"
                 : !smooth        ? "  (shading normal: the same, no vertex normals)"
                 : h.n_s == h.n_g ? "  (shading normal: blended vertex normals, here the same as n_g)"
                                  : "  (shading normal: blended vertex normals)")
             << "\n";
        if (h.n_c != Vec3{})
            out_ << "  n_c      " << readable(h.n_c)
                 << "  (the clearcoat's own normal: its clearcoatNormalTexture, or n_s "
                 << "without the base's map)\n";
        out_ << "  ω_o      " << readable(-v.ray_dir) << "  (towards the viewer)\n";
        out_ << "  material " << material_text(h, c_.scene.materials[h.material]) << "\n";
        emission(v.emission, "emission");

        if (v.delta_material) {
            out_ << "  lights   none: a perfectly specular surface reflects a point light in one direction only,\n"
                    "           never towards this viewer (its BRDF is a delta)\n";
        } else if (v.delta_lights.empty() && c_.job.lights.delta.empty()) {
            out_ << "  point, spot and directional lights: none in the scene\n";
        }
        for (const DeltaLightRecord& l : v.delta_lights) delta_light(l, v.throughput);
        if (r_.path && !v.delta_material) sampled_light(v.sampled_light);
        if (r_.path) bounce(v);
    }

    std::string medium_name(std::uint32_t medium) const {
        return medium == kNoMedium ? std::string("vacuum") : "medium \"" + c_.scene.media[medium].name + "\"";
    }

    // Spec §26: the interfaces the arriving ray crossed and the media it went through.
    void media(const VertexRecord& v) {
        std::size_t next_crossing = 0;
        auto crossings_before = [&](std::size_t segment) {
            for (; next_crossing < v.crossings.size() && v.crossings[next_crossing].after_segments <= segment;
                 ++next_crossing) {
                const CrossingRecord& c = v.crossings[next_crossing];
                out_ << "  crosses  the interface " << where(c.triangle, c.instance) << " at distance "
                     << readable(c.distance) << ", into " << medium_name(c.medium_after) << "\n";
            }
        };
        for (std::size_t i = 0; i < v.segments.size(); ++i) {
            crossings_before(i);
            const MediumSegmentRecord& m = v.segments[i];
            out_ << "  through  " << medium_name(m.medium) << " for "
                 << (std::isfinite(m.distance) ? readable(m.distance) : std::string("ever (nothing ahead)"))
                 << (m.scattered ? ", where the path scatters" : "") << "\n";
            out_ << "    free-flight weight " << readable(m.weight)
                 << (m.scattered ? "  (T·σ_s/p(t): transmittance to the event, scattering, over its density)"
                                 : "  (T/P(no event): transmittance over the chance of passing)")
                 << "\n";
            if (m.emission != Vec3{0.0f})
                out_ << "    the medium's own light adds β·∫T·ε = " << readable(m.emission) << "\n";
        }
        crossings_before(v.segments.size());
    }

    // A scattering event: the phase function in the BSDF's place.
    void medium_event(const VertexRecord& v) {
        const Medium& m = c_.scene.media[v.medium];
        out_ << "  scatters in " << medium_name(v.medium) << " at x = " << readable(v.position) << "\n";
        out_ << "  phase    Henyey–Greenstein, g = " << readable(m.g)
             << "  (it plays f_r, with no cosine: p(ω_o, ω_i) integrates to 1)\n";
        if (v.delta_lights.empty() && c_.job.lights.delta.empty())
            out_ << "  point, spot and directional lights: none in the scene\n";
        for (const DeltaLightRecord& l : v.delta_lights) delta_light(l, v.throughput, true);
        sampled_light(v.sampled_light, true);
        bounce(v);
    }

    // The cut-outs a ray went through (spec §12): surfaces that are not
    // there. `lead` starts the first line, `indent` the others.
    void holes(const std::vector<HoleRecord>& listed, std::size_t crossed, const char* lead, const char* indent) {
        if (crossed == 0) return;
        out_ << lead << crossed << (crossed == 1 ? " cut-out" : " cut-outs")
             << " (alpha below the cutoff: no surface there)\n";
        for (const HoleRecord& h : listed)
            out_ << indent << where(h.triangle) << " at t " << readable(h.t) << ": alpha " << readable(h.alpha) << " < "
                 << readable(h.cutoff) << "\n";
        if (crossed > listed.size()) out_ << indent << "and " << crossed - listed.size() << " more\n";
    }

    void emission(const EmissionRecord& e, const char* what) {
        if (!e.present) {
            out_ << "  " << what << " L_e = 0\n";
            return;
        }
        out_ << "  " << what << " L_e = " << readable(e.radiance);
        if (e.bsdf_pdf > 0.0f)
            out_ << ", MIS weight " << readable(e.mis_weight) << " (BSDF pdf " << readable(e.bsdf_pdf)
                 << " vs light pdf " << readable(e.light_pdf) << ")";
        out_ << "\n    adds β·L_e·w = " << readable(e.contribution) << "\n";
    }

    void blocked(const BlockerRecord& b, const char* tail) {
        if (b.triangle == kNoTriangle) {
            out_ << "    BLOCKED: the media on the shadow ray's way take all of its light (transmittance 0)\n";
            return;
        }
        out_ << "    BLOCKED: the shadow ray meets " << where(b.triangle, b.instance) << " at distance "
             << readable(b.distance) << tail << "\n";
    }

    // At a medium vertex (`medium`) the phase function stands for f_r and there is no cosine.
    void delta_light(const DeltaLightRecord& l, Vec3 beta, bool medium = false) {
        const PunctualLight& light = c_.job.lights.delta[l.light];
        const LightTypeTraits type = light_type_traits(light.type);
        // What arrives, named as its factor in the equation; the column of
        // '=' moves right for a name longer than the others'.
        const std::string incident = delta_incident_symbol(light.type);
        const std::size_t width = std::max<std::size_t>(kFactorColumn, characters(incident) + 1);
        const std::string pad(width - characters(incident), ' ');
        const std::string wide(width - kFactorColumn, ' ');
        out_ << "  " << type.name << " light " << l.light;
        if (type.positioned) out_ << " at " << readable(light.position);
        if (type.directed)
            out_ << (type.positioned ? " pointing along " : " travelling along ") << readable(light.direction);
        out_ << ", " << type.power_symbol << " = " << readable(light.intensity);
        if (type.coned)
            out_ << ", cone cos " << readable(light.cos_outer) << " (outer) to " << readable(light.cos_inner)
                 << " (inner)";
        out_ << "\n";
        if (l.outcome == LightOutcome::OnSurface) {
            out_ << "    sits exactly on x: it lights nothing\n";
            return;
        }
        out_ << "    ω_i = " << readable(l.wi)
             << ", |c − x| = " << (type.positioned ? readable(l.distance) : "unbounded")
             << (medium ? std::string() : ", n_g·ω_i = " + readable(l.cos_g)) << "\n";
        if (l.outcome == LightOutcome::Behind) {
            out_ << "    BEHIND the surface (n_g·ω_i ≤ 0): no contribution\n";
            return;
        }
        if (type.coned) out_ << "    spot falloff s² = " << readable(l.spot_factor) << "\n";
        if (l.outcome == LightOutcome::OutsideCone) {
            out_ << "    OUTSIDE the spot's cone (s = 0): no contribution\n";
            return;
        }
        if (l.outcome == LightOutcome::Blocked) {
            blocked(l.blocker, type.positioned ? ", before the light" : "");
            out_ << "    (unblocked it would give " << incident << " = " << readable(l.incident)
                 << (medium ? ", phase p = " + readable(l.f.x)
                            : ", f_r = " + readable(l.f) + ", |n_s·ω_i| = " + readable(l.cos_s))
                 << ")\n";
            return;
        }
        out_ << "    visible\n";
        holes(l.holes, l.holes_crossed, "    the shadow ray went through ", "      ");
        out_ << "    " << incident << pad << "= " << readable(l.incident) << "\n";
        if (medium) {
            out_ << "    phase p    " << wide << "= " << readable(l.f.x) << "\n";
        } else {
            out_ << "    f_r        " << wide << "= " << readable(l.f) << " = " << lobe_sum(l.f_terms) << "\n";
            out_ << "    |n_s·ω_i|  " << wide << "= " << readable(l.cos_s) << "\n";
        }
        if (l.transmittance != Vec3{1.0f})
            out_ << "    T          " << wide << "= " << readable(l.transmittance)
                 << "  (transmittance of the media on the way)\n";
        if (r_.path) out_ << "    β          " << wide << "= " << readable(beta) << "\n";
        out_ << "    product    " << wide << "= " << readable(l.contribution) << "\n";
    }

    void sampled_light(const SampledLightRecord& l, bool medium = false) {
        if (!l.sampled) {
            if (!c_.job.lights.has_sampled_lights()) return;
            out_ << "  sampled light: none this time (the sample fell on a light's dark side or carries nothing)\n";
            return;
        }
        out_ << "  sampled light " << l.light << ": "
             << (l.environment ? std::string("the environment") : where(l.triangle, l.instance)) << "\n";
        out_ << "    ω_i = " << readable(l.wi);
        if (!l.environment)
            out_ << ", point " << readable(l.target) << ", distance " << readable(l.distance)
                 << ", |n_light·ω_i| = " << readable(l.cos_light);
        out_ << "\n    L_e = " << readable(l.radiance) << ", light pdf = " << readable(l.light_pdf) << " /sr, "
             << (medium ? "phase pdf = " : "BSDF pdf = ") << readable(l.bsdf_pdf) << " /sr\n";
        if (l.outcome == LightOutcome::Behind) {
            out_ << "    BEHIND the surface (n_g·ω_i ≤ 0): f_r = 0, no shadow ray, no contribution\n";
            return;
        }
        if (l.outcome == LightOutcome::Blocked) {
            blocked(l.blocker, "");
            return;
        }
        if (l.f == Vec3{0.0f}) {
            out_ << "    f_r = 0 in this direction: no shadow ray, no contribution\n";
            return;
        }
        holes(l.holes, l.holes_crossed, "    the shadow ray went through ", "      ");
        if (medium)
            out_ << "    phase p = " << readable(l.f.x) << "\n";
        else
            out_ << "    f_r = " << readable(l.f) << " = " << lobe_sum(l.f_terms)
                 << ", |n_s·ω_i| = " << readable(l.cos_s) << "\n";
        if (l.transmittance != Vec3{1.0f})
            out_ << "    T = " << readable(l.transmittance) << "  (transmittance of the media on the way)\n";
        out_ << "    MIS weight w = " << readable(l.mis_weight) << " (power heuristic)\n";
        out_ << (medium ? "    adds β·p·L_e·w/pdf" : "    adds β·f_r·|n_s·ω_i|·L_e·w/pdf")
             << (l.transmittance != Vec3{1.0f} ? "·T" : "") << " = " << readable(l.contribution) << "\n";
    }

    void bounce(const VertexRecord& v) {
        const BounceRecord& b = v.bounce;
        if (&v == &r_.vertices.back() && !b.sampled && r_.end.find("max_depth") != std::string::npos) return;
        if (!b.sampled) {
            if (&v == &r_.vertices.back()) out_ << "  bounce: the BSDF sampled no direction\n";
            return;
        }
        out_ << "  bounce: ω_i = " << readable(b.wi) << (b.delta ? " (specular)" : "")
             << (b.transmission ? " (refracted)" : "") << (v.medium_event ? " (from the phase function)" : "") << "\n";
        if (v.medium_event)
            out_ << "    p = pdf = " << readable(b.pdf) << " /sr: sampled exactly, weight 1\n";
        else if (b.delta)
            out_ << "    lobe chosen with probability " << readable(b.pdf) << ", weight " << readable(b.weight) << "\n";
        else
            out_ << "    f_r = " << readable(b.f) << ", pdf = " << readable(b.pdf)
                 << " /sr, weight f_r·|cos|/pdf = " << readable(b.weight) << "\n";
        out_ << "    throughput β = " << readable(b.throughput) << "\n";
        if (b.roulette) {
            out_ << "    Russian roulette: survival probability q = " << readable(b.roulette_q)
                 << ", drew u = " << readable(b.roulette_u)
                 << (b.survived ? " < q: survives, β/q = " + readable(b.throughput_after) : " ≥ q: the path ends")
                 << "\n";
        }
    }

    void total() {
        out_ << "\nThe path ends: " << r_.end << "\n";
        out_ << "\nValue of this sample\n";
        if (r_.nonfinite) out_ << "  the sum was not a finite number; it counts as 0 (nonfinite_samples)\n";
        out_ << "  L = " << exact(r_.value) << "\n";
        const int spp = c_.job.settings.spp;
        if (spp == 1)
            out_ << "  with one sample per pixel this is the pixel's value in the rendered image (linear RGB)\n";
        else
            out_ << "  the pixel's value is the average of its " << spp
                 << " samples (sombra explain ... --sample K shows each)\n";
    }

    const ExplainContext& c_;
    const SampleRecord& r_;
    std::ostringstream out_;
};

}  // namespace

std::string explain_text(const ExplainContext& context, const SampleRecord& record) {
    return Story(context, record).tell();
}

}  // namespace sombra
