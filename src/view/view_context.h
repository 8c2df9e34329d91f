// What the viewer's request handlers share (internal to src/view/).
#pragma once

#include <atomic>
#include <string>

#include "image/image_io.h"
#include "scene/scene.h"
#include "view/live_render.h"

namespace httplib {
class Server;
}

namespace sombra {

struct ViewContext {
    const Scene& scene;
    LiveRender& live;
    std::string scene_file;
    DisplayTransform display;     // the page's starting exposure and tone mapper
    std::atomic<int> streams{0};  // event streams open now
};

// Adds the routes of the page, the state, the camera and settings, the
// images and the event stream (view_routes.cpp).
void add_view_routes(httplib::Server& server, ViewContext& context);

// Adds /explain (view_explain.cpp).
void add_explain_route(httplib::Server& server, ViewContext& context);

}  // namespace sombra
