// `sombra view SCENE`: load and build as `render` does, then serve the
// render to a browser (src/view/, spec §20) until Ctrl-C.
#include <iostream>

#include "accel/accel.h"
#include "api/session.h"
#include "app/interrupt.h"
#include "app/report.h"
#include "app/run.h"
#include "core/error.h"
#include "io/scene_input.h"
#include "render/render.h"
#include "view/view_server.h"

namespace sombra {

int run_view(const CliOptions& o) {
    RenderProgress progress;
    InterruptWatcher interrupt(progress);  // first: before any other thread starts
    return reporting_errors(o.input, [&] {
        Diagnostics diag;
        LoadedScene input = load_input(o.input, diag);
        Scene& scene = input.scene;
        const RenderSettings settings = resolve_settings(input.settings, o.render.overrides);
        print_warnings(diag, scene, settings, o.render, o.input);
        prepare_scene(scene, settings, o.render, o.input);
        const Accel accel = make_accel(scene, o.render.accel);

        ViewServerOptions options;
        options.initial = ViewSettings{scene.camera, settings};
        options.threads = o.render.threads;
        options.light_selection = o.render.light_selection;
        options.display = o.display;
        options.denoise = o.render.denoise;
        options.port = o.port;
        options.scene_file = o.input;
        ViewServer server(scene, accel, options);
        interrupt.on_interrupt([&server] { server.stop(); });
        interrupt.set_phase(InterruptWatcher::Phase::Serving);
        // The URL on stdout, alone on its line, for scripts; the hint on stderr.
        std::cout << server.url() << std::endl;
        if (!o.quiet) std::cerr << "sombra: serving " << one_line_message(o.input) << " on 127.0.0.1; Ctrl-C ends it\n";
        if (interrupt.signal_received() != 0) return 0;  // a signal before Serving
        if (!server.run()) throw Error("127.0.0.1:" + std::to_string(server.port()), "serving failed");
        interrupt.set_phase(InterruptWatcher::Phase::Writing);
        interrupt.on_interrupt({});
        if (!o.quiet) std::cerr << "sombra: view ended\n";
        return 0;
    });
}

}  // namespace sombra
