// `sombra explain SCENE X Y`: load and build as `render` does, trace the one
// sample with a recorder, and tell its story (spec §14). Under --denoise the
// whole image is rendered and denoised as `render --denoise` does, and the
// story adds the pixel's denoising (spec §25).
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <optional>

#include "accel/accel.h"
#include "api/session.h"
#include "app/interrupt.h"
#include "app/progress.h"
#include "app/report.h"
#include "app/run.h"
#include "core/error.h"
#include "denoise/denoise.h"
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

// The whole image of `job`, with a progress bar on a terminal unless `quiet`.
RenderOutput render_whole(const RenderJob& job, RenderProgress& progress, bool quiet) {
    const RenderSettings& s = job.settings;
    const bool show = !quiet && isatty(STDERR_FILENO);
    ProgressBar bar(progress,
                    static_cast<std::uint64_t>(s.width) * static_cast<std::uint64_t>(s.height) *
                        static_cast<std::uint64_t>(s.spp),
                    show);
    return render_image(job, progress);
}

// The one line for a run that a signal stopped, and its exit status.
int report_interrupted(const InterruptWatcher& interrupt) {
    const int sig = interrupt.signal_received();
    std::cerr << "sombra: error: " << signal_name(sig) << ": interrupted, nothing written\n";
    return interrupted_exit_status(sig);
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
        // As `render` resolves them: under --denoise a scene of 1 spp is a command-line error.
        const RenderSettings settings = resolve_render_settings(input.settings, o.render);
        print_warnings(diag, scene, settings, o.render, o.input);
        check_explain_pixel(o.pixel_x, o.pixel_y, o.sample, settings);
        prepare_scene(scene, settings, o.render, o.input);

        const Accel accel = make_accel(scene, o.render.accel);
        const RenderJob job = make_job(scene, accel, settings, o.render, std::chrono::steady_clock::now());
        const SampleRecord record = record_pixel_sample(job, o.pixel_x, o.pixel_y, o.sample);

        // Under --denoise: the image render --denoise makes from the same
        // job, and the weights that made this pixel of it.
        RenderOutput rendered;
        std::optional<DenoiseStory> denoised;
        if (o.render.denoise) {
            interrupt.set_phase(InterruptWatcher::Phase::Rendering);
            rendered = render_whole(job, progress, o.quiet);
            if (rendered.cancelled) return report_interrupted(interrupt);
            const std::size_t p = (static_cast<std::size_t>(o.pixel_y) * static_cast<std::size_t>(settings.width) +
                                   static_cast<std::size_t>(o.pixel_x)) *
                                  3;
            denoised =
                DenoiseStory{explain_denoised_pixel(rendered.aovs.denoise, o.pixel_x, o.pixel_y, o.render.threads),
                             {rendered.film.rgb[p], rendered.film.rgb[p + 1], rendered.film.rgb[p + 2]}};
            if (progress.cancel.load()) return report_interrupted(interrupt);
        }

        const ExplainContext context{scene, job, o.input, denoised ? &*denoised : nullptr};
        // The whole story is made before any of it is printed or written.
        const std::string story = o.json ? explain_json(context, record) : explain_text(context, record);

        if (!o.svg.empty()) {
            // The picture shows the render that was denoised, or else a quick one.
            if (!denoised) {
                RenderJob preview = job;
                preview.settings.spp = picture_spp(settings);
                interrupt.set_phase(InterruptWatcher::Phase::Rendering);
                rendered = render_whole(preview, progress, o.quiet);
                if (rendered.cancelled) return report_interrupted(interrupt);
            }
            interrupt.set_phase(InterruptWatcher::Phase::Writing);
            const std::string picture =
                explain_svg(context, record,
                            ImageView{rendered.film.width, rendered.film.height, rendered.film.rgb.data()}, o.display);
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
