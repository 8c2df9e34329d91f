// `sombra explain SCENE X Y`: load and build as `render` does, trace the one
// sample with a recorder, and tell its story (spec §14).
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>

#include "accel/accel.h"
#include "api/session.h"
#include "app/interrupt.h"
#include "app/progress.h"
#include "app/report.h"
#include "app/run.h"
#include "core/error.h"
#include "explain/explain.h"
#include "image/atomic_file.h"
#include "io/scene_input.h"
#include "render/render.h"

namespace sombra {

namespace {

// The picture's file must be writable, found out before the work.
void check_svg_path(const std::filesystem::path& path) {
    if (lower_extension(path) != ".svg")
        throw Error(path.string(), "the picture is an SVG file: the name must end in .svg");
    check_side_file_path(path);
}

}  // namespace

int run_explain(const CliOptions& o) {
    RenderProgress progress;
    InterruptWatcher interrupt(progress);  // first: before any other thread starts
    return reporting_errors(o.input, [&] {
        if (!o.svg.empty()) check_svg_path(o.svg);
        Diagnostics diag;
        LoadedScene input = load_input(o.input, diag);
        Scene& scene = input.scene;
        const RenderSettings settings = resolve_settings(input.settings, o.render.overrides);
        print_warnings(diag, scene, settings, o.input);
        check_explain_pixel(o.pixel_x, o.pixel_y, o.sample, settings);
        prepare_scene(scene, settings, o.render, o.input);

        const Accel accel = make_accel(scene, o.render.accel);
        const RenderJob job = make_job(scene, accel, settings, o.render, std::chrono::steady_clock::now());
        const SampleRecord record = record_pixel_sample(job, o.pixel_x, o.pixel_y, o.sample);

        const ExplainContext context{scene, job, o.input};
        // The whole story is made before any of it is printed or written.
        const std::string story = o.json ? explain_json(context, record) : explain_text(context, record);

        if (!o.svg.empty()) {
            RenderJob preview = job;
            preview.settings.spp = picture_spp(settings);
            interrupt.set_phase(InterruptWatcher::Phase::Rendering);
            RenderOutput rendered;
            {
                const bool show = !o.quiet && isatty(STDERR_FILENO);
                ProgressBar bar(progress,
                                static_cast<std::uint64_t>(settings.width) *
                                    static_cast<std::uint64_t>(settings.height) *
                                    static_cast<std::uint64_t>(preview.settings.spp),
                                show);
                rendered = render_image(preview, progress);
            }
            if (rendered.cancelled) {
                const int sig = interrupt.signal_received();
                std::cerr << "sombra: error: " << signal_name(sig) << ": interrupted, nothing written\n";
                return interrupted_exit_status(sig);
            }
            interrupt.set_phase(InterruptWatcher::Phase::Writing);
            const std::string picture =
                explain_svg(context, record,
                            ImageView{rendered.film.width, rendered.film.height, rendered.film.rgb.data()}, o.exposure);
            write_file_atomically(o.svg, [&picture](const std::filesystem::path& temp) {
                std::ofstream out(temp, std::ios::binary);
                out << picture;
                out.close();
                if (!out) throw Error(temp.string(), "write failed");
            });
        }
        std::cout << story << std::flush;
        return 0;
    });
}

}  // namespace sombra
