#include "app/run.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <tbb/info.h>

#include "accel/accel.h"
#include "app/interrupt.h"
#include "app/progress.h"
#include "app/stats.h"
#include "core/error.h"
#include "core/peak_rss.h"
#include "image/image_io.h"
#include "render/render.h"
#include "scene/scene_file.h"

namespace sombra {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// Each message stays one line whatever the paths in it hold: control
// characters (a newline or NUL in a file name) are shown as '?'.
std::string one_line(std::string text) {
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text;
}

Scene load_input(const std::filesystem::path& input, Diagnostics& diag) {
    const std::string ext = lower_extension(input);
    if (ext == ".json") return load_scene_file(input, diag);
    if (ext == ".obj" || ext == ".ply" || ext == ".gltf" || ext == ".glb") return make_quicklook_scene(input, diag);
    throw Error(input.string(),
                "unknown input type '" + ext + "' (expected a scene .json, or a model .obj, .ply, .gltf or .glb)");
}

// Applies the command line's overrides to the scene's render settings,
// checking each against the same limits as the scene file's values (which
// the loader already checked, so a problem names the option that caused it).
RenderSettings resolve_settings(const RenderSettings& scene_settings, const CliOptions& o) {
    RenderSettings s = scene_settings;
    auto check = [&s](const char* option) {
        if (const std::string problem = render_settings_problem(s); !problem.empty()) throw Error(option, problem);
    };
    if (o.width) { s.width = *o.width; check("--width"); }
    if (o.height) { s.height = *o.height; check("--height"); }
    if (o.spp) { s.spp = *o.spp; check("--spp"); }
    if (o.seed) s.seed = *o.seed;
    if (o.integrator) s.integrator = *o.integrator == "path" ? IntegratorKind::Path : IntegratorKind::Direct;
    if (o.max_depth) { s.max_depth = *o.max_depth; check("--max-depth"); }
    return s;
}

// The statistics file's folder must exist: found out before the render, not after.
void check_stats_path(const std::filesystem::path& path) {
    const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec)) throw Error(path.string(), "folder '" + folder.string() + "' does not exist");
    if (std::filesystem::is_directory(path, ec)) throw Error(path.string(), "is a folder");
}

}  // namespace

int run_render(const CliOptions& o) {
    const auto start = Clock::now();
    RenderProgress progress;
    InterruptWatcher interrupt(progress);  // first: before any other thread starts
    try {
        const std::filesystem::path output = o.output;
        // Fail before a long render, not after it.
        check_output_path(output);
        if (!o.stats_json.empty()) check_stats_path(o.stats_json);

        RunStats stats;
        Diagnostics diag;
        const auto load_start = Clock::now();
        Scene scene = load_input(o.input, diag);
        stats.load_seconds = seconds_since(load_start);
        for (const std::string& w : diag.warnings) std::cerr << "sombra: warning: " << one_line(w) << '\n';

        const RenderSettings settings = resolve_settings(scene.render, o);
        // After the overrides: --integrator path silences it, --integrator direct may cause it.
        if (settings.integrator == IntegratorKind::Direct && needs_path_integrator(scene))
            std::cerr << "sombra: warning: " << one_line(o.input)
                      << ": the direct integrator lights with point lights only: quad lights and the environment "
                         "are only seen, mirror and glass reflect nothing from point lights; use --integrator path\n";
        const AccelKind kind = *parse_accel_kind(o.accel);  // the command line checked the name

        const auto build_start = Clock::now();
        const Accel accel = make_accel(scene.geometry, kind);
        stats.build_seconds = seconds_since(build_start);

        const LightSelection selection = o.light_tree == "on"    ? LightSelection::Tree
                                         : o.light_tree == "off" ? LightSelection::Power
                                                                 : LightSelection::Automatic;
        const RenderJob job = make_render_job(scene, accel, settings, o.threads, selection);

        interrupt.set_phase(InterruptWatcher::Phase::Rendering);
        const auto render_start = Clock::now();
        RenderOutput rendered;
        {
            const bool show = !o.quiet && isatty(STDERR_FILENO);
            ProgressBar bar(progress,
                            static_cast<std::uint64_t>(settings.width) * static_cast<std::uint64_t>(settings.height) *
                                static_cast<std::uint64_t>(settings.spp),
                            show);
            rendered = render_image(job, progress);
        }
        stats.render_seconds = seconds_since(render_start);
        if (rendered.cancelled) {
            const int sig = interrupt.signal_received();
            std::cerr << "sombra: error: " << signal_name(sig) << ": interrupted, nothing written\n";
            return interrupted_exit_status(sig);
        }
        interrupt.set_phase(InterruptWatcher::Phase::Writing);

        const auto write_start = Clock::now();
        write_image(output, ImageView{rendered.film.width, rendered.film.height, rendered.film.rgb.data()}, o.exposure);
        stats.write_seconds = seconds_since(write_start);

        stats.triangles = scene.geometry.triangle_count();
        stats.width = settings.width;
        stats.height = settings.height;
        stats.spp = settings.spp;
        stats.threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
        stats.accel = std::string(accel_name(kind));
        stats.accel_bytes = accel_memory_bytes(accel);
        stats.integrator = settings.integrator == IntegratorKind::Path ? "path" : "direct";
        stats.max_depth = settings.max_depth;
        stats.bounce_rays = rendered.counters.bounce_rays;
        stats.camera_rays = rendered.counters.camera_rays;
        stats.shadow_rays = rendered.counters.shadow_rays;
        stats.nonfinite_samples = rendered.counters.nonfinite_samples;
        stats.peak_rss_bytes = peak_rss_bytes();
        stats.total_seconds = seconds_since(start);
        if (!o.stats_json.empty()) write_stats_json(o.stats_json, stats);
        if (!o.quiet) std::cerr << summary_line(stats, o.output) << '\n';
        return 0;
    } catch (const Error& e) {
        std::cerr << "sombra: error: " << one_line(e.where() + ": " + e.message()) << '\n';
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "sombra: error: " << one_line(o.input) << ": out of memory\n";
        return 1;
    } catch (const std::exception& e) {
        // A bug, not the input's fault; still one line and no image.
        std::cerr << "sombra: error: " << one_line(o.input) << ": internal error: " << one_line(e.what()) << '\n';
        return 1;
    }
}

int run_sombra(int argc, const char* const* argv) {
    const CliParse parsed = parse_command_line(argc, argv);
    if (!parsed.options) return parsed.exit_code;
    return run_render(*parsed.options);
}

}  // namespace sombra
