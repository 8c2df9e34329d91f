// GET /explain?x=X&y=Y[&sample=K]: explain's story (spec §14) of pixel
// (X, Y)'s sample K at the viewer's current camera and settings, as one JSON
// object: "json" (what `sombra explain --json` prints), "text" (what it
// prints without --json) and "svg" (the picture of --svg, drawn beside the
// viewer's current image).
#include <httplib.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "api/session.h"
#include "explain/explain.h"
#include "view/query_values.h"
#include "view/view_context.h"

namespace sombra {

namespace {

void explain_pixel(ViewContext& c, const httplib::Request& req, httplib::Response& res) {
    const ViewSettings s = c.live.settings();
    std::string problem;
    std::optional<int> x, y, sample = 0;
    if (req.has_param("x")) x = parse_query_int("x", req.get_param_value("x"), 0, s.settings.width - 1, problem);
    if (x && req.has_param("y")) y = parse_query_int("y", req.get_param_value("y"), 0, s.settings.height - 1, problem);
    if (x && y && req.has_param("sample"))
        sample = parse_query_int("sample", req.get_param_value("sample"), 0, s.settings.spp - 1, problem);
    if (!x || !y || !sample) {
        res.status = 400;
        res.set_content("400 bad request: " + (problem.empty() ? std::string("x and y are required") : problem) + "\n",
                        "text/plain");
        return;
    }
    const RenderJob job = c.live.job_for(s);
    const SampleRecord record = record_pixel_sample(job, *x, *y, *sample);
    const ExplainContext context{c.scene, job, c.scene_file};

    std::shared_ptr<const Film> image = c.live.latest().shown();
    if (!image || image->width != s.settings.width || image->height != s.settings.height)
        image = std::make_shared<const Film>(s.settings.width, s.settings.height);
    const nlohmann::json answer = {
        {"json", nlohmann::json::parse(explain_json(context, record))},
        {"text", explain_text(context, record)},
        {"svg", explain_svg(context, record, ImageView{image->width, image->height, image->rgb.data()}, c.display)}};
    res.set_content(answer.dump(), "application/json");
}

}  // namespace

void add_explain_route(httplib::Server& server, ViewContext& c) {
    server.Get("/explain", [&c](const httplib::Request& req, httplib::Response& res) { explain_pixel(c, req, res); });
}

}  // namespace sombra
