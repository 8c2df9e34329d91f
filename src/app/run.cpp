#include "app/run.h"

#include <fcntl.h>
#include <unistd.h>

#include <tbb/info.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "accel/accel.h"
#include "api/session.h"
#include "app/display_server.h"
#include "app/interrupt.h"
#include "app/progress.h"
#include "app/report.h"
#include "app/stats.h"
#include "core/error.h"
#include "core/peak_rss.h"
#include "denoise/denoise_layers.h"
#include "distributed/mpi_render.h"
#include "distributed/shards.h"
#include "image/image_io.h"
#include "io/scene_input.h"
#include "render/render.h"

namespace sombra {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The AOV images as the EXR channels spec §18 and §25 name: those `asked`
// for, the denoiser's under their names (denoise/denoise_layers.h), and
// the image before denoising when `noisy` is given.
std::vector<ImageChannel> aov_layers(const AovImages& aovs, const AovSet& asked, const Film* noisy) {
    std::vector<ImageChannel> layers;
    auto add3 = [&layers](const std::vector<float>& image, const char* layer, const char* axes) {
        if (image.empty()) return;
        for (int c = 0; c < 3; ++c) layers.push_back({std::string(layer) + "." + axes[c], image.data() + c, 3});
    };
    add3(aovs.albedo, "albedo", "RGB");
    add3(aovs.normal, "normal", "XYZ");
    if (!aovs.depth.empty()) layers.push_back({"depth.Z", aovs.depth.data(), 1});
    add3(aovs.position, "position", "XYZ");
    if (!aovs.spp.empty()) layers.push_back({"spp.Y", aovs.spp.data(), 1});
    // The denoiser's layers hold the same variance.
    if (!asked.denoise) add3(aovs.variance, "variance", "RGB");
    if (noisy != nullptr) add3(noisy->rgb, "noisy", "RGB");
    if (asked.denoise)
        for_each_denoise_channel(aovs.denoise, [&layers](const std::string& name, const std::vector<float>& values,
                                                         int component, int stride) {
            layers.push_back({name, values.data() + component, stride});
        });
    return layers;
}

// Under --display-server the render goes in passes (the image after n
// samples is the same as in one pass: render/accumulation.h), and tev gets
// the image after a pass at most every kDisplayInterval; the final image is
// sent after the render. A plain --spp render takes passes of a sixteenth
// of its samples (at least one); --time and --noise-threshold keep theirs.
constexpr auto kDisplayInterval = std::chrono::milliseconds(250);

void stream_passes_to(DisplayConnection& display, RenderJob& job) {
    if (!display.connected()) return;
    if (!job.limits.deadline && !(job.limits.noise_threshold > 0))
        job.limits.pass_samples = std::max(1, job.settings.spp / 16);
    job.on_pass = [&display, last = Clock::time_point{}](const Accumulation& acc, int) mutable {
        if (!display.connected() || Clock::now() - last < kDisplayInterval) return;
        const Film image = acc.mean_image();
        display.show(ImageView{image.width, image.height, image.rgb.data()});
        last = Clock::now();
    };
}

// One image of the run: rendered, written to `output`, its counters added
// to `stats`. Returns the exit status (non-zero when interrupted). Under
// mpirun a still is rendered by all ranks and written by rank 0 alone.
int render_frame(const CliOptions& o, const Scene& scene, const Accel& accel, const RenderSettings& settings,
                 const std::filesystem::path& output, Clock::time_point start, InterruptWatcher& interrupt,
                 RenderProgress& progress, RunStats& stats, const MpiRun& mpi) {
    const bool distributed = mpi.active() && !o.first_frame;
    RenderJob job = make_job(scene, accel, settings, o.render, start);
    // With --frames, --shard splits frames, not pixels (spec §21).
    const bool pixel_shard = o.sharded && !o.first_frame;
    if (pixel_shard) job.shard = ShardSpec{o.shard_index, o.shard_count};
    // A shard's header says which share it is, of which render (spec §21).
    // With --crop and --denoise it splits the grown window, and says where the crop lies in it.
    std::optional<PixelWindow> kept;
    if (o.render.crop && job.window && !(*job.window == *o.render.crop))
        kept = PixelWindow{o.render.crop->x0 - job.window->x0, o.render.crop->y0 - job.window->y0, o.render.crop->width,
                           o.render.crop->height};
    const std::vector<ImageAttribute> shard_header =
        pixel_shard ? shard_attributes(o.input, o.render, settings, job.shard, kept) : std::vector<ImageAttribute>{};
    std::optional<DisplayConnection> display;
    if (!o.display_server.empty()) {
        display.emplace(*parse_display_address(o.display_server), output.filename().string(), settings.width,
                        settings.height);
        stream_passes_to(*display, job);
    }

    interrupt.set_phase(InterruptWatcher::Phase::Rendering);
    const auto render_start = Clock::now();
    RenderOutput rendered;
    {
        const bool show = !o.quiet && isatty(STDERR_FILENO) && mpi.rank() == 0;
        ProgressBar bar(progress,
                        shard_pixel_count(job.shard, job.window ? job.window->width : settings.width,
                                          job.window ? job.window->height : settings.height) *
                            static_cast<std::uint64_t>(settings.spp),
                        show, job.limits.deadline);
        rendered = distributed ? mpi.render(job, progress) : render_image(job, progress);
    }
    stats.render_seconds += seconds_since(render_start);
    if (display && !rendered.cancelled)
        display->show(ImageView{rendered.film.width, rendered.film.height, rendered.film.rgb.data()});
    if (rendered.cancelled) {
        const int sig = interrupt.signal_received();
        std::cerr << "sombra: error: " << signal_name(sig) << ": interrupted, nothing written\n";
        return interrupted_exit_status(sig);
    }
    if (distributed && mpi.rank() != 0) return 0;  // rank 0 has the image

    // A shard is denoised once merged (sombra merge --denoise): it carries the denoiser's layers.
    AovSet written = o.render.aovs;
    if (pixel_shard && o.render.denoise) written.denoise = true;
    Film noisy;
    if (o.render.denoise && !pixel_shard) {
        const auto denoise_start = Clock::now();
        noisy = denoise_render(rendered, job, o.render);
        stats.denoise_seconds += seconds_since(denoise_start);
        if (progress.cancel.load()) {
            const int sig = interrupt.signal_received();
            std::cerr << "sombra: error: " << signal_name(sig) << ": interrupted, nothing written\n";
            return interrupted_exit_status(sig);
        }
    }
    interrupt.set_phase(InterruptWatcher::Phase::Writing);

    const auto write_start = Clock::now();
    write_image(output, ImageView{rendered.film.width, rendered.film.height, rendered.film.rgb.data()}, o.display,
                aov_layers(rendered.aovs, written, o.render.aovs.noisy ? &noisy : nullptr), shard_header);
    stats.write_seconds += seconds_since(write_start);

    stats.spp =
        o.render.time_budget && !o.render.overrides.spp ? static_cast<int>(rendered.max_pixel_spp) : settings.spp;
    stats.spp_uniform = rendered.min_pixel_spp == rendered.max_pixel_spp;
    stats.spp_reached =
        static_cast<double>(rendered.samples) / static_cast<double>(std::max<std::uint64_t>(rendered.pixels, 1));
    if (stats.spp_uniform) stats.spp_reached = rendered.max_pixel_spp;
    stats.passes = rendered.passes;
    stats.bounce_rays += rendered.counters.bounce_rays;
    stats.camera_rays += rendered.counters.camera_rays;
    stats.shadow_rays += rendered.counters.shadow_rays;
    stats.nonfinite_samples += rendered.counters.nonfinite_samples;
    return 0;
}

// Points standard error at /dev/null (a rank that is not rank 0).
void silence_stderr() {
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null < 0) return;
    std::fflush(stderr);
    ::dup2(null, STDERR_FILENO);
    ::close(null);
}

// Why `o` cannot run as K > 1 ranks, as a command-line problem (exit 2), or
// nothing: --time and --noise-threshold on a still (a block would take the
// budget, a stopping rule reads neighbours in other blocks), --shard,
// --display-server, or a build without MPI.
std::optional<std::string> mpi_option_problem(const CliOptions& o) {
    if (std::string why; !mpi_available(&why))
        return "this sombra cannot run under mpirun: its MPI plugin " + why +
               " (install the sombra-mpi package, or build with Open MPI)";
    if (o.sharded) return "--shard and mpirun cannot go together: mpirun already splits the work";
    if (!o.display_server.empty()) return "--display-server and mpirun cannot go together";
    if (!o.first_frame && o.render.time_budget)
        return "--time and mpirun cannot go together on one image: the budget is per process (use --spp)";
    if (!o.first_frame && o.render.noise_threshold)
        return "--noise-threshold and mpirun cannot go together on one image: a pixel's stopping reads its "
               "neighbours, which another rank renders (it works with --frames)";
    return std::nullopt;
}

}  // namespace

// The frames a run renders (spec §22): --frames' range (every Nth of it
// under --shard I/N or as rank I of N under mpirun), --frame, or the
// scene's first frame.
std::vector<std::int64_t> frames_to_render(const CliOptions& o, const Scene& scene, int rank, int ranks) {
    if (o.first_frame) {
        std::vector<std::int64_t> frames;
        const int index = o.sharded ? o.shard_index : rank;
        const std::int64_t step = o.sharded ? o.shard_count : ranks;
        for (std::int64_t f = *o.first_frame + index; f <= *o.last_frame; f += step) frames.push_back(f);
        return frames;
    }
    if (o.render.frame) return {*o.render.frame};
    return {scene.animation ? scene.animation->first_frame : 0};
}

int run_render(const CliOptions& options) {
    const auto start = Clock::now();
    RenderProgress progress;
    InterruptWatcher interrupt(progress);  // first: before any other thread starts
    // Under a launcher (mpirun -np K, K > 1), checked before MPI starts.
    if (const LaunchedRanks launched = launched_ranks(); launched.size > 1) {
        if (const auto problem = mpi_option_problem(options)) {
            if (launched.rank == 0) std::cerr << "sombra: error: command line: " << *problem << '\n';
            return 2;
        }
    }
    const MpiRun mpi;  // starts MPI only under a launcher
    // Ranks that share one image say nothing: rank 0 reports for all (its
    // error, warnings, the summary), and the launcher ends the others with
    // SIGTERM once it stops. Frames are each rank's own, and so are their words.
    const bool silent = mpi.active() && mpi.rank() != 0 && !options.first_frame;
    if (silent) silence_stderr();
    CliOptions o = options;
    o.render.threads = mpi.threads_per_rank(o.render.threads);
    const bool writes = mpi.rank() == 0 || o.first_frame;  // under mpirun frames are written by their rank
    const int exit_status = reporting_errors(o.input, [&] {
        // Fail before a long render, not after it.
        if (writes) check_output_path(o.output);
        if (!o.stats_json.empty() && mpi.rank() == 0) check_side_file_path(o.stats_json);

        RunStats stats;
        Diagnostics diag;
        const auto load_start = Clock::now();
        LoadedScene input = load_input(o.input, diag);
        Scene& scene = input.scene;
        stats.load_seconds = seconds_since(load_start);
        // Under a time budget the scene's spp does not limit the passes; --spp does (spec §18).
        const RenderSettings settings = resolve_render_settings(input.settings, o.render);
        print_warnings(diag, scene, settings, o.render, o.input);
        const AccelKind kind = o.render.accel;

        const auto mipmap_start = Clock::now();
        prepare_textures(scene, settings);
        stats.mipmap_seconds = seconds_since(mipmap_start);

        // Every frame, the first included, is placed by set_scene_time, so
        // that --frame F and frame F of --frames are the same scene bit for bit.
        const std::vector<std::int64_t> frames = frames_to_render(o, scene, mpi.rank(), mpi.size());
        const auto time_of = [&](std::int64_t frame) { return frame_time(scene, frame); };
        if (scene.animation && !frames.empty()) set_scene_time(scene, time_of(frames.front()), o.input);
        const auto build_start = Clock::now();
        Accel accel = make_accel(scene, kind);
        stats.build_seconds = seconds_since(build_start);

        for (std::size_t i = 0; i < frames.size(); ++i) {
            if (i > 0 && scene.animation) {
                // A new moment moves instances only: the meshes' structures stay (spec §22).
                set_scene_time(scene, time_of(frames[i]), o.input);
                const auto refit_start = Clock::now();
                update_instances(accel, scene);
                stats.build_seconds += seconds_since(refit_start);
            }
            const std::string output = o.first_frame ? frame_file_name(o.output, frames[i]) : o.output;
            if (const int status =
                    render_frame(o, scene, accel, settings, output, start, interrupt, progress, stats, mpi);
                status != 0)
                return status;
        }
        if (mpi.active() && o.first_frame) {
            // Each rank rendered its frames; rank 0 reports the rays of all.
            const RayCounters all =
                mpi.sum({stats.camera_rays, stats.shadow_rays, stats.bounce_rays, stats.nonfinite_samples});
            stats.camera_rays = all.camera_rays;
            stats.shadow_rays = all.shadow_rays;
            stats.bounce_rays = all.bounce_rays;
            stats.nonfinite_samples = all.nonfinite_samples;
        }
        if (mpi.rank() != 0) return 0;

        stats.triangles = stored_triangle_count(scene);
        stats.instanced_triangles = drawn_triangle_count(scene);
        stats.frames = o.first_frame && !o.sharded ? static_cast<std::uint64_t>(*o.last_frame - *o.first_frame + 1)
                                                   : frames.size();
        stats.processes = mpi.size();
        // The image written: the --crop window's size (spec §27).
        stats.width = o.render.crop ? o.render.crop->width : settings.width;
        stats.height = o.render.crop ? o.render.crop->height : settings.height;
        stats.threads = o.render.threads > 0 ? o.render.threads : tbb::info::default_concurrency();
        stats.accel = std::string(accel_name(kind));
        stats.accel_bytes = accel_memory_bytes(accel);
        stats.integrator = std::string(integrator_name(settings.integrator));
        stats.max_depth = settings.max_depth;
        stats.texture_filter = std::string(texture_filter_name(settings.texture_filter));
        stats.peak_rss_bytes = peak_rss_bytes();
        stats.total_seconds = seconds_since(start);
        if (!o.stats_json.empty()) write_stats_json(o.stats_json, stats);
        if (!o.quiet) std::cerr << summary_line(stats, o.output) << '\n';
        return 0;
    });
    // One rank's failure ends every rank, before rank 0 could write an image.
    if (exit_status != 0 && mpi.active()) {
        // Another rank may be aborting too: its SIGTERM must not add a second line.
        interrupt.set_phase(InterruptWatcher::Phase::Failed);
        // A silent rank's failure (a missing scene) is rank 0's too, which
        // says it: give rank 0 the time to abort first, so that it is not
        // ended before it could. A failure of this rank alone still ends the job.
        if (silent) std::this_thread::sleep_for(std::chrono::seconds(1));
        mpi.abort(exit_status);
    }
    return exit_status;
}

int run_sombra(int argc, const char* const* argv) {
    const CliParse parsed = parse_command_line(argc, argv);
    if (!parsed.options) return parsed.exit_code;
    if (parsed.options->command == Command::Explain) return run_explain(*parsed.options);
    if (parsed.options->command == Command::View) return run_view(*parsed.options);
    if (parsed.options->command == Command::Merge) return run_merge(*parsed.options);
    if (parsed.options->command == Command::Denoise) return run_denoise(*parsed.options);
    return run_render(*parsed.options);
}

}  // namespace sombra
