// The viewer's routes: the page, its state, the camera and settings it
// sends, the images and the event stream announcing each pass.
#include <httplib.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/error.h"
#include "image/display_transform.h"
#include "image/image_io.h"
#include "view/query_values.h"
#include "view/view_camera.h"
#include "view/view_context.h"
#include "view/view_page.h"
#include "view/view_server.h"

namespace sombra {

namespace {

using nlohmann::json;

// The event stream wakes at least this often to notice a closed page or a stopping server.
constexpr std::chrono::milliseconds kStreamTick{500};

json vec3_json(Vec3 v) { return json::array({v.x, v.y, v.z}); }

json frame_json(const ViewFrame& f) {
    return {{"version", f.version},
            {"generation", f.generation},
            {"passes", f.passes},
            {"spp", f.spp},
            {"target_spp", f.target_spp},
            {"seconds", f.seconds},
            {"passes_per_second", f.seconds > 0 ? f.passes / f.seconds : 0.0},
            {"done", f.done},
            {"denoise", f.denoise},
            {"denoised", f.denoised},
            {"denoised_spp", f.denoised_spp}};
}

json state_json(const ViewContext& c) {
    const ViewSettings s = c.live.settings();
    const RenderJob job = c.live.job_for(s);
    const CameraLookAt camera = view_camera_of(s.camera, job.camera);
    json camera_state = {
        {"origin", vec3_json(camera.origin)}, {"look_at", vec3_json(camera.look_at)}, {"up", vec3_json(camera.up)}};
    if (s.camera.projection == CameraSpec::Projection::Orthographic) {
        camera_state["projection"] = "orthographic";
        camera_state["half_height"] = s.camera.ortho_half_height;
    } else {
        camera_state["projection"] = "perspective";
        camera_state["fov"] = camera.fov_degrees;
    }
    const ViewFrame frame = c.live.latest();
    return {{"scene", c.scene_file},
            {"width", s.settings.width},
            {"height", s.settings.height},
            {"spp", s.settings.spp},
            {"max_depth", s.settings.max_depth},
            {"integrator", integrator_name(s.settings.integrator)},
            {"denoise", frame.denoise},
            {"exposure", c.display.exposure},
            {"tonemap", tonemap_name(c.display.tonemap)},
            {"camera", camera_state},
            {"frame", frame_json(frame)}};
}

void bad_request(httplib::Response& res, const std::string& problem) {
    res.status = 400;
    res.set_content("400 bad request: " + problem + "\n", "text/plain");
}

// The parameter `name`, or nullopt when the request has none.
std::optional<std::string> param(const httplib::Request& req, const char* name) {
    if (!req.has_param(name)) return std::nullopt;
    return req.get_param_value(name);
}

// POST /camera?origin=x,y,z&look_at=x,y,z&up=x,y,z&fov=F: every value
// required, checked as the scene file's; an orthographic camera takes
// half_height=H instead of fov.
void set_camera(ViewContext& c, const httplib::Request& req, httplib::Response& res) {
    std::string problem;
    CameraLookAt camera;
    const char* names[3] = {"origin", "look_at", "up"};
    Vec3* targets[3] = {&camera.origin, &camera.look_at, &camera.up};
    for (int k = 0; k < 3; ++k) {
        const std::optional<std::string> text = param(req, names[k]);
        if (!text) return bad_request(res, std::string("missing ") + names[k]);
        const std::optional<Vec3> v = parse_query_vec3(names[k], *text, problem);
        if (!v) return bad_request(res, problem);
        *targets[k] = *v;
    }
    ViewSettings s = c.live.settings();
    const bool orthographic = s.camera.projection == CameraSpec::Projection::Orthographic;
    const char* zoom_name = orthographic ? "half_height" : "fov";
    const char* other_name = orthographic ? "fov" : "half_height";
    if (param(req, other_name))
        return bad_request(res, std::string("the scene's camera is ") +
                                    (orthographic ? "orthographic" : "perspective") + ": it takes " + zoom_name +
                                    ", not " + other_name);
    const std::optional<std::string> zoom_text = param(req, zoom_name);
    if (!zoom_text) return bad_request(res, std::string("missing ") + zoom_name);
    const std::optional<double> zoom = parse_query_number(zoom_name, *zoom_text, problem);
    if (!zoom) return bad_request(res, problem);
    std::optional<float> half_height;
    if (orthographic) {
        if (const std::string p = view_half_height_problem(*zoom); !p.empty()) return bad_request(res, p);
        half_height = static_cast<float>(*zoom);
    } else {
        camera.fov_degrees = static_cast<float>(*zoom);
    }
    if (const std::string p = view_camera_problem(camera); !p.empty()) return bad_request(res, p);
    s.camera = with_view_camera(s.camera, camera, half_height);
    c.live.restart(s);
    res.set_content(state_json(c).dump(), "application/json");
}

// POST /settings?integrator=direct|path&spp=N&max_depth=D&denoise=on|off:
// each optional. The denoise switch alone does not restart the passes
// (LiveRender::set_denoise decides); anything else does.
void set_settings(ViewContext& c, const httplib::Request& req, httplib::Response& res) {
    std::string problem;
    ViewSettings s = c.live.settings();
    std::optional<bool> denoise;
    if (const std::optional<std::string> text = param(req, "denoise")) {
        if (*text != "on" && *text != "off") return bad_request(res, "denoise must be on or off");
        denoise = *text == "on";
    }
    if (const std::optional<std::string> integrator = param(req, "integrator")) {
        if (*integrator != "direct" && *integrator != "path")
            return bad_request(res, "integrator must be direct or path");
        s.settings.integrator = *integrator == "path" ? IntegratorKind::Path : IntegratorKind::Direct;
    }
    if (const std::optional<std::string> text = param(req, "spp")) {
        const std::optional<int> spp = parse_query_int("spp", *text, 1, kMaxSpp, problem);
        if (!spp) return bad_request(res, problem);
        s.settings.spp = *spp;
    }
    if (const std::optional<std::string> text = param(req, "max_depth")) {
        const std::optional<int> depth = parse_query_int("max_depth", *text, 0, kMaxDepth, problem);
        if (!depth) return bad_request(res, problem);
        s.settings.max_depth = *depth;
    }
    if (const std::string p = render_settings_problem(s.settings); !p.empty()) return bad_request(res, p);
    const bool others = req.has_param("integrator") || req.has_param("spp") || req.has_param("max_depth");
    if (others || !denoise) c.live.restart(s);
    if (denoise) c.live.set_denoise(*denoise);
    res.set_content(state_json(c).dump(), "application/json");
}

// The image the page shows (the newest denoised pass under the denoise
// switch), or a black one of the right size before the first pass.
std::shared_ptr<const Film> current_image(const ViewContext& c) {
    if (std::shared_ptr<const Film> image = c.live.latest().shown()) return image;
    const RenderSettings s = c.live.settings().settings;
    return std::make_shared<const Film>(s.width, s.height);
}

void send_png(ViewContext& c, const httplib::Request& req, httplib::Response& res) {
    DisplayTransform display = c.display;
    if (const std::optional<std::string> text = param(req, "exposure")) {
        std::string problem;
        const std::optional<double> e = parse_query_number("exposure", *text, problem);
        if (!e || std::abs(*e) > 64)
            return bad_request(res, problem.empty() ? "exposure must lie in [-64, 64]" : problem);
        display.exposure = static_cast<float>(*e);
    }
    if (const std::optional<std::string> name = param(req, "tonemap")) {
        try {
            display.tonemap = tonemap_option(*name);
        } catch (const Error& e) {
            return bad_request(res, "tonemap: " + e.message());
        }
    }
    const std::shared_ptr<const Film> image = current_image(c);
    const std::vector<std::uint8_t> png =
        encode_png_bytes(ImageView{image->width, image->height, image->rgb.data()}, display);
    res.set_content(std::string(png.begin(), png.end()), "image/png");
}

void send_exr(ViewContext& c, httplib::Response& res) {
    const std::shared_ptr<const Film> image = current_image(c);
    const std::vector<std::uint8_t> exr = encode_exr_bytes(ImageView{image->width, image->height, image->rgb.data()});
    res.set_header("Content-Disposition", "attachment; filename=\"sombra-view.exr\"");
    res.set_content(std::string(exr.begin(), exr.end()), "image/x-exr");
}

// GET /events: one "pass" event at once, then one for each new pass,
// denoised image or turn of the denoise switch; a comment line when nothing
// happened for a while, which also finds a closed page. A client that stops reading blocks only its own request thread, and
// only until the write times out; the render never waits for it.
void stream_events(ViewContext& c, httplib::Response& res) {
    if (c.streams.fetch_add(1) >= kMaxViewStreams) {
        c.streams.fetch_sub(1);
        res.status = 503;
        res.set_content("503 too many event streams open\n", "text/plain");
        return;
    }
    auto sent = std::make_shared<std::optional<std::uint64_t>>();
    res.set_chunked_content_provider(
        "text/event-stream",
        [&c, sent](std::size_t, httplib::DataSink& sink) {
            if (c.live.stopped()) {
                sink.done();
                return true;
            }
            const ViewFrame frame = *sent ? c.live.wait_newer(**sent, kStreamTick) : c.live.latest();
            if (c.live.stopped()) {
                sink.done();
                return true;
            }
            std::string message = ": waiting\n\n";
            if (!*sent || frame.updates != **sent) {
                message = "event: pass\ndata: " + frame_json(frame).dump() + "\n\n";
                *sent = frame.updates;
            }
            return sink.write(message.data(), message.size());
        },
        [&c](bool) { c.streams.fetch_sub(1); });
}

}  // namespace

void add_view_routes(httplib::Server& server, ViewContext& c) {
    server.Get("/", [](const httplib::Request&, httplib::Response& res) {
        res.set_content(std::string(kViewPage), "text/html; charset=utf-8");
    });
    server.Get("/state", [&c](const httplib::Request&, httplib::Response& res) {
        res.set_content(state_json(c).dump(), "application/json");
    });
    server.Post("/camera", [&c](const httplib::Request& req, httplib::Response& res) { set_camera(c, req, res); });
    server.Post("/settings", [&c](const httplib::Request& req, httplib::Response& res) { set_settings(c, req, res); });
    server.Get("/image.png", [&c](const httplib::Request& req, httplib::Response& res) { send_png(c, req, res); });
    server.Get("/image.exr", [&c](const httplib::Request&, httplib::Response& res) { send_exr(c, res); });
    server.Get("/events", [&c](const httplib::Request&, httplib::Response& res) { stream_events(c, res); });
}

}  // namespace sombra
