// `sombra view` (spec §20): an HTTP server on 127.0.0.1 that shows the
// render refining pass by pass in a browser and lets the user move the
// camera, change the settings, save the image and ask `explain` about a
// pixel. The page is the one in src/view/page.html, built into the binary;
// no request reaches the file system.
//
// Security: the server listens on loopback only; every request must carry
// the random token of the URL it prints (`?token=…`), a Host header naming
// 127.0.0.1:PORT or localhost:PORT, and no Origin but its own (else 403;
// no CORS headers are ever sent). Requests are bounded (request line and
// each header 8 KiB, body kMaxViewBody), and so are the event streams
// (kMaxViewStreams at once).
#pragma once

#include <memory>
#include <string>

#include "accel/accel.h"
#include "image/image_io.h"
#include "render/lights/lights.h"
#include "scene/scene.h"
#include "view/live_render.h"

namespace sombra {

inline constexpr std::size_t kMaxViewBody = 16 * 1024;
inline constexpr int kMaxViewStreams = 16;

struct ViewServerOptions {
    ViewSettings initial;  // the scene's camera and settings with the command line's overrides
    int threads = 0;       // render threads; 0 = all hardware threads
    LightSelection light_selection = LightSelection::Automatic;
    DisplayTransform display;  // the page's starting exposure and tone mapper
    bool denoise = false;      // the denoise switch's starting state (spec §25)
    int port = 0;              // 0 = a free port the system picks
    std::string scene_file;    // for explain's story and the page's title
    std::string token;         // empty = make_view_token()
};

class ViewServer {
public:
    // Binds 127.0.0.1:port and starts the render. Throws
    // Error("--port", ...) when the port cannot be bound.
    ViewServer(const Scene& scene, const Accel& accel, const ViewServerOptions& options);
    ~ViewServer();
    ViewServer(const ViewServer&) = delete;
    ViewServer& operator=(const ViewServer&) = delete;

    int port() const;
    const std::string& token() const;
    // "http://127.0.0.1:PORT/?token=TOKEN": what the user opens.
    std::string url() const;
    LiveRender& render();

    // Serves requests until stop(); returns false when serving failed.
    bool run();
    // Ends run() at once from any thread: the event streams close, the port is freed.
    void stop();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace sombra
