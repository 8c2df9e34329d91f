// The story as a picture: the scene's outlines seen from above and to the
// right of the camera (orthographic, so nothing hides anything), with the
// camera, the path, the lights and every shadow ray drawn on top, beside the
// rendered image with the pixel marked.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/base64.h"
#include "explain/describe.h"
#include "explain/explain.h"
#include "explain/explain_denoise.h"
#include "explain/outline.h"
#include "explain/side_view.h"
#include "explain/svg_markup.h"

namespace sombra {

namespace {

constexpr float kPanel = 480.0f;  // height of both panels, width of the scene view is 4/3 of it
constexpr float kViewWidth = 640.0f;
constexpr float kGap = 24.0f;
constexpr float kMargin = 16.0f;
constexpr std::size_t kOutlineBudget = 30000;

const char* const kPathColour = "#1f5fd0";
const char* const kVisibleColour = "#d89a00";
const char* const kBlockedColour = "#d0202a";
const char* const kBehindColour = "#909090";
const char* const kNormalColour = "#1a9850";

// Short, for the many coordinates below.
std::string num(float v) { return svg_number(v); }

class Picture {
public:
    Picture(const ExplainContext& context, const SampleRecord& record)
        : c_(context), r_(record), view_(context.job.camera) {}

    std::string draw(ImageView image, DisplayTransform display) {
        fit();
        const float image_scale =
            std::min(kPanel / static_cast<float>(image.width), kPanel / static_cast<float>(image.height));
        const float image_w = image_scale * static_cast<float>(image.width),
                    image_h = image_scale * static_cast<float>(image.height);
        const float image_panel = std::max(image_w, 200.0f);
        const float width = kViewWidth + kGap + image_panel + (c_.denoised ? kGap + kDenoiseMapWidth : 0.0f);
        const std::vector<CaptionLine> lines = story_lines();
        const float height = kPanel + 80.0f + 16.0f * static_cast<float>(std::min(lines.size(), kMaxStoryLines));
        svg_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\"" << num(height)
             << "\" viewBox=\"0 0 " << num(width) << " " << num(height)
             << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
        svg_ << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
        svg_ << "<clipPath id=\"view\"><rect width=\"" << num(kViewWidth) << "\" height=\"" << num(kPanel)
             << "\"/></clipPath>\n";
        svg_ << "<rect width=\"" << num(kViewWidth) << "\" height=\"" << num(kPanel)
             << "\" fill=\"#fafafa\" stroke=\"#ccc\"/>\n";
        svg_ << "<g clip-path=\"url(#view)\">\n";
        outlines();
        camera();
        lights();
        path();
        svg_ << "</g>\n";
        rendered_image(image, display, kViewWidth + kGap, image_w, image_h);
        if (c_.denoised)
            svg_ << denoise_weight_map(*c_.denoised, r_.pixel_x, r_.pixel_y, kViewWidth + kGap + image_panel + kGap, 0);
        caption(lines, height);
        svg_ << "</svg>\n";
        return svg_.str();
    }

private:
    // The view covers the camera, the path and the lights, and the scene
    // unless the scene is much larger than they are (a vast ground plane).
    void fit() {
        Point2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
        auto add = [&](Vec3 p) {
            if (!is_finite(p)) return;
            const Point2 q = view_.flat(p);
            lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
            hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
        };
        add(r_.origin);
        for (const VertexRecord& v : r_.vertices)
            if (v.hit || v.medium_event) add(v.medium_event ? v.position : v.surface.position);
        for (const PunctualLight& l : c_.job.lights.delta)
            if (light_type_traits(l.type).positioned) add(l.position);  // a light at infinity has no place
        const Point2 interest_lo = lo, interest_hi = hi;
        Point2 scene_lo{INFINITY, INFINITY}, scene_hi{-INFINITY, -INFINITY};
        for (const Vec3 p : c_.scene.geometry.positions) {
            if (!is_finite(p)) continue;
            const Point2 q = view_.flat(p);
            scene_lo = {std::min(scene_lo.x, q.x), std::min(scene_lo.y, q.y)};
            scene_hi = {std::max(scene_hi.x, q.x), std::max(scene_hi.y, q.y)};
        }
        const float interest = std::max(interest_hi.x - interest_lo.x, interest_hi.y - interest_lo.y);
        const float scene = std::max(scene_hi.x - scene_lo.x, scene_hi.y - scene_lo.y);
        if (scene_lo.x <= scene_hi.x && !(scene > 4.0f * interest && interest > 0.0f)) {
            lo = {std::min(lo.x, scene_lo.x), std::min(lo.y, scene_lo.y)};
            hi = {std::max(hi.x, scene_hi.x), std::max(hi.y, scene_hi.y)};
        } else if (interest > 0.0f) {
            const float pad = 0.5f * interest;
            lo = {lo.x - pad, lo.y - pad};
            hi = {hi.x + pad, hi.y + pad};
        }
        if (!(lo.x <= hi.x)) lo = hi = {0, 0};
        view_.fit(lo, hi, kViewWidth, kPanel, kMargin);
    }

    void line(Vec3 a, Vec3 b, const char* colour, float width, const char* dash = nullptr) {
        const Point2 p = view_.screen(a), q = view_.screen(b);
        svg_ << "<line x1=\"" << num(p.x) << "\" y1=\"" << num(p.y) << "\" x2=\"" << num(q.x) << "\" y2=\"" << num(q.y)
             << "\" stroke=\"" << colour << "\" stroke-width=\"" << num(width) << "\"";
        if (dash) svg_ << " stroke-dasharray=\"" << dash << "\"";
        svg_ << "/>\n";
    }

    void dot_at(Vec3 p, const char* colour, float radius) {
        const Point2 q = view_.screen(p);
        svg_ << "<circle cx=\"" << num(q.x) << "\" cy=\"" << num(q.y) << "\" r=\"" << num(radius) << "\" fill=\""
             << colour << "\"/>\n";
    }

    // Text beside a point; in the right part of the view it ends at the point instead, to stay inside.
    void label(Vec3 p, const std::string& text, const char* colour, float dx = 6, float dy = -6) {
        const Point2 q = view_.screen(p);
        const bool right = q.x > 0.6f * kViewWidth && dx > 0;
        svg_ << "<text x=\"" << num(right ? q.x - dx : q.x + dx) << "\" y=\"" << num(q.y + dy) << "\" fill=\"" << colour
             << "\"" << (right ? " text-anchor=\"end\"" : "") << ">" << escape_xml(text) << "</text>\n";
    }

    void cross_at(Vec3 p, const char* colour) {
        const Point2 q = view_.screen(p);
        constexpr float k = 5;
        svg_ << "<path d=\"M" << num(q.x - k) << " " << num(q.y - k) << "L" << num(q.x + k) << " " << num(q.y + k)
             << "M" << num(q.x - k) << " " << num(q.y + k) << "L" << num(q.x + k) << " " << num(q.y - k)
             << "\" stroke=\"" << colour << "\" stroke-width=\"2.5\"/>\n";
    }

    void outlines() {
        const std::vector<Segment> segments = outline_segments(c_.scene.geometry, view_.direction(), kOutlineBudget);
        svg_ << "<path fill=\"none\" stroke=\"#8a8a8a\" stroke-width=\"0.7\" d=\"";
        for (const Segment& s : segments) {
            const Point2 a = view_.screen(s.a), b = view_.screen(s.b);
            svg_ << "M" << num(a.x) << " " << num(a.y) << "L" << num(b.x) << " " << num(b.y);
        }
        svg_ << "\"/>\n";
        // Emitting triangles (quad lights, ke) in the light's colour, when there are few.
        const LightSet& lights = c_.job.lights;
        if (lights.emitters.size() <= 2000) {
            svg_ << "<path fill=\"#ffd54f\" fill-opacity=\"0.6\" stroke=\"#e0a000\" stroke-width=\"1\" d=\"";
            for (const Emitter& e : lights.emitters) {
                const std::array<Vec3, 3> corners = world_triangle_corners(c_.scene, e.triangle, e.instance);
                for (int k = 0; k < 3; ++k) {
                    const Point2 p = view_.screen(corners[static_cast<std::size_t>(k)]);
                    svg_ << (k == 0 ? "M" : "L") << num(p.x) << " " << num(p.y);
                }
                svg_ << "Z";
            }
            svg_ << "\"/>\n";
        }
    }

    void camera() {
        const Camera& cam = c_.job.camera;
        if (cam.orthographic) {
            orthographic_camera(cam);
            return;
        }
        const float k = 0.08f * view_.extent() / std::max(length(cam.forward), 1e-12f);
        Vec3 corners[4];
        for (int i = 0; i < 4; ++i)
            corners[i] =
                cam.origin + k * (cam.forward + (i & 1 ? 1.0f : -1.0f) * cam.left + (i & 2 ? 1.0f : -1.0f) * cam.up);
        for (const Vec3 c : corners) line(cam.origin, c, "#333", 1);
        line(corners[0], corners[1], "#333", 1);
        line(corners[1], corners[3], "#333", 1);
        line(corners[3], corners[2], "#333", 1);
        line(corners[2], corners[0], "#333", 1);
        label(cam.origin, "camera", "#333", 4, 18);
    }

    // The rectangle the parallel rays leave (its true size) and a box along
    // their direction, where a pinhole camera has its pyramid.
    void orthographic_camera(const Camera& cam) {
        const Vec3 depth = 0.08f * view_.extent() * cam.forward;
        Vec3 near[4], far[4];
        for (int i = 0; i < 4; ++i) {
            near[i] = cam.origin + (i & 1 ? 1.0f : -1.0f) * cam.left + (i & 2 ? 1.0f : -1.0f) * cam.up;
            far[i] = near[i] + depth;
            line(near[i], far[i], "#333", 1);
        }
        for (const Vec3* r : {near, far}) {
            line(r[0], r[1], "#333", 1);
            line(r[1], r[3], "#333", 1);
            line(r[3], r[2], "#333", 1);
            line(r[2], r[0], "#333", 1);
        }
        label(cam.origin, "camera (orthographic)", "#333", 4, 18);
    }

    void lights() {
        const std::vector<PunctualLight>& delta = c_.job.lights.delta;
        for (std::size_t i = 0; i < delta.size(); ++i) {
            if (!light_type_traits(delta[i].type).positioned) continue;  // drawn as its shadow rays only
            const Vec3 p = delta[i].position;
            const Point2 q = view_.screen(p);
            svg_ << "<circle cx=\"" << num(q.x) << "\" cy=\"" << num(q.y)
                 << "\" r=\"7\" fill=\"#ffd54f\" stroke=\"#b07800\" "
                 << "stroke-width=\"1.5\"/>\n";
            label(p, "light " + std::to_string(i), "#7a5300", 9, 4);
        }
    }

    std::string object_name(std::uint32_t triangle, std::uint32_t instance = kNoInstance) const {
        if (triangle == kNoTriangle) return "the media on the way (transmittance 0)";
        const TriangleOrigin o = triangle_origin(c_.scene, triangle, instance);
        std::string name = o.file.empty() ? o.object : o.file.substr(o.file.find_last_of('/') + 1);
        return name + instance_words(o) + " triangle " + std::to_string(o.triangle) + " (" + o.material + ")";
    }

    // A shadow ray from x towards `target`: solid to the light when it gets
    // there, red to the blocker (marked ×) and dashed beyond when it does not.
    void shadow_ray(Vec3 x, Vec3 target, LightOutcome outcome, const BlockerRecord& blocker) {
        if (outcome == LightOutcome::Visible) {
            line(x, target, kVisibleColour, 1.8f);
        } else if (outcome == LightOutcome::Blocked) {
            const Vec3 dir = normalize(target - x);
            const Vec3 at = x + blocker.distance * dir;
            line(x, at, kBlockedColour, 2.2f);
            line(at, target, kBlockedColour, 1, "4 4");
            cross_at(at, kBlockedColour);
            // Named in the view when the story is short; a long path's caption names each blocker instead.
            if (r_.vertices.size() <= 2)
                label(at, "blocked by " + object_name(blocker.triangle, blocker.instance), kBlockedColour);
        } else if (outcome == LightOutcome::Behind || outcome == LightOutcome::OutsideCone) {
            line(x, target, kBehindColour, 1, "2 4");
        }
    }

    void path() {
        Vec3 from = r_.origin;
        for (const VertexRecord& v : r_.vertices) {
            if (!v.hit && !v.medium_event) {
                line(from, from + 0.3f * view_.extent() * v.ray_dir, kPathColour, 2.2f, "8 4");
                label(from + 0.3f * view_.extent() * v.ray_dir, "leaves the scene", kPathColour);
                break;
            }
            const Vec3 x = v.medium_event ? v.position : v.surface.position;
            line(from, x, kPathColour, 2.2f);
            for (const DeltaLightRecord& l : v.delta_lights) {
                // Toward a light at infinity the ray has no end: drawn as far as the environment's.
                const PunctualLight& light = c_.job.lights.delta[l.light];
                const Vec3 target =
                    light_type_traits(light.type).positioned ? light.position : x + 0.3f * view_.extent() * l.wi;
                shadow_ray(x, target, l.outcome, l.blocker);
            }
            const SampledLightRecord& s = v.sampled_light;
            if (s.sampled) {
                const Vec3 target = s.environment ? x + 0.3f * view_.extent() * s.wi : s.target;
                shadow_ray(x, target, s.outcome, s.blocker);
                dot_at(target, "#e0a000", 3);
            }
            if (!v.medium_event) line(x, x + 0.06f * view_.extent() * v.surface.n_s, kNormalColour, 1.5f);
            dot_at(x, kPathColour, 4);
            // append, not "x" + to_string(), here and below: GCC 12's
            // -Wrestrict misfires on operator+(const char*, string&&) (its bug 105329).
            label(x, std::string("x").append(std::to_string(v.depth)), kPathColour, -16, -6);
            from = x;
        }
    }

    void rendered_image(ImageView image, DisplayTransform display, float left, float w, float h) {
        const std::vector<std::uint8_t> png = encode_png_bytes(image, display);
        svg_ << "<image x=\"" << num(left) << "\" y=\"0\" width=\"" << num(w) << "\" height=\"" << num(h)
             << "\" preserveAspectRatio=\"none\" style=\"image-rendering:pixelated\" href=\"data:image/png;base64,"
             << base64_encode(std::string_view(reinterpret_cast<const char*>(png.data()), png.size())) << "\"/>\n";
        const float s = w / static_cast<float>(image.width);
        const float px = left + s * static_cast<float>(r_.pixel_x), py = s * static_cast<float>(r_.pixel_y);
        const float size = std::max(s, 1.0f);
        svg_ << "<rect x=\"" << num(px - 0.5f) << "\" y=\"" << num(py - 0.5f) << "\" width=\"" << num(size + 1)
             << "\" height=\"" << num(size + 1) << "\" fill=\"none\" stroke=\"#ff2020\" stroke-width=\"1\"/>\n";
        svg_ << "<circle cx=\"" << num(px + size * 0.5f) << "\" cy=\"" << num(py + size * 0.5f)
             << "\" r=\"12\" fill=\"none\" stroke=\"#ff2020\" stroke-width=\"2\"/>\n";
        svg_ << "<text x=\"" << num(left) << "\" y=\"" << num(h + 16) << "\">the render (" << image.width << "x"
             << image.height << ", "
             << (c_.denoised ? std::to_string(c_.job.settings.spp) + " spp, before denoising"
                             : std::to_string(picture_spp(c_.job.settings)) + " spp")
             << "), pixel (" << r_.pixel_x << ", " << r_.pixel_y << ") circled</text>\n";
    }

    void text_line(float y, const std::string& text, const char* colour = "#222") {
        svg_ << "<text x=\"8\" y=\"" << num(y) << "\" fill=\"" << colour << "\">" << escape_xml(text) << "</text>\n";
    }

    struct CaptionLine {
        std::string text;
        const char* colour;
    };

    CaptionLine light_line(const std::string& name, LightOutcome outcome, const BlockerRecord& blocker,
                           Vec3 contribution) const {
        switch (outcome) {
            case LightOutcome::Visible:
                return {name + ": reaches the light, adds " + readable(contribution), kVisibleColour};
            case LightOutcome::Blocked:
                return {name + ": blocked by " + object_name(blocker.triangle, blocker.instance) + " at distance " +
                            readable(blocker.distance),
                        kBlockedColour};
            case LightOutcome::Behind: return {name + ": behind the surface, adds nothing", kBehindColour};
            case LightOutcome::OnSurface: return {name + ": on the surface, adds nothing", kBehindColour};
            case LightOutcome::OutsideCone: return {name + ": outside the spot's cone, adds nothing", kBehindColour};
        }
        return {name, kBehindColour};
    }

    // Why the sample is as bright as it is, one line per light term: the
    // first vertex's lights under `direct`, every vertex's under `path`.
    std::vector<CaptionLine> story_lines() const {
        std::vector<CaptionLine> lines;
        lines.push_back({"Pixel (" + std::to_string(r_.pixel_x) + ", " + std::to_string(r_.pixel_y) + "), sample " +
                             std::to_string(r_.sample) + ": L = " + readable(r_.value) + "   (" + r_.end + ")",
                         "#222"});
        for (const VertexRecord& v : r_.vertices) {
            const std::string at = r_.path ? std::string("x").append(std::to_string(v.depth)).append(" ") : "";
            if (v.medium_event) {
                lines.push_back({at + "scatters in medium \"" + c_.scene.media[v.medium].name + "\", throughput " +
                                     readable(v.throughput),
                                 kPathColour});
            } else if (!v.hit) {
                lines.push_back({at + "leaves the scene: environment L_e = " + readable(v.emission.radiance) +
                                     ", adds " + readable(v.emission.contribution),
                                 kPathColour});
                continue;
            } else if (r_.path) {
                lines.push_back({at + "on " + object_name(v.surface.triangle, v.surface.instance) + ", throughput " +
                                     readable(v.throughput) +
                                     (v.emission.present ? ", emission adds " + readable(v.emission.contribution) : ""),
                                 kPathColour});
            }
            for (const DeltaLightRecord& l : v.delta_lights)
                lines.push_back(
                    light_line("  " + at + "light " + std::to_string(l.light), l.outcome, l.blocker, l.contribution));
            const SampledLightRecord& s = v.sampled_light;
            if (s.sampled)
                lines.push_back(light_line("  " + at + (s.environment ? "environment sample" : "emitter sample"),
                                           s.outcome, s.blocker, s.contribution));
        }
        return lines;
    }

    static constexpr std::size_t kMaxStoryLines = 12;

    void caption(const std::vector<CaptionLine>& lines, float height) {
        float y = kPanel + 20;
        for (std::size_t i = 0; i < lines.size() && i < kMaxStoryLines; ++i, y += 16)
            text_line(y,
                      i + 1 == kMaxStoryLines && lines.size() > kMaxStoryLines ? "… (the text story has the rest)"
                                                                               : lines[i].text,
                      lines[i].colour);
        text_line(height - 42,
                  "The scene seen from above and to the right of the camera (orthographic, outlines only).", "#555");
        text_line(height - 26,
                  "Blue: camera ray and path (x0, x1, …); green: shading normal n_s; gold: shadow ray that reaches its "
                  "light;",
                  "#555");
        text_line(
            height - 10,
            "red: blocked shadow ray (× marks the blocker, dashed beyond it); grey dots: light behind the surface.",
            "#555");
    }

    const ExplainContext& c_;
    const SampleRecord& r_;
    SideView view_;
    std::ostringstream svg_;
};

}  // namespace

std::string explain_svg(const ExplainContext& context, const SampleRecord& record, ImageView image,
                        DisplayTransform display) {
    return Picture(context, record).draw(image, display);
}

}  // namespace sombra
