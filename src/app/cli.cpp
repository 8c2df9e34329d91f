#include "app/cli.h"

#include <CLI/CLI.hpp>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <iostream>
#include <type_traits>
#include <vector>

#include "accel/accel.h"
#include "app/cli_suggest.h"
#include "app/display_server.h"
#include "core/error.h"
#include "image/display_transform.h"
#include "image/image_io.h"
#include "render/render_settings.h"

namespace sombra {

namespace {

// The most shards one render may be split into (spec §21): far more than a
// cluster's nodes, far fewer than an image's blocks.
constexpr int kMaxShards = 4096;

// CLI11 messages can span lines; the contract wants one.
std::string one_line(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// A number option checked by the library's own check (check_render_options)
// on `set`'s field, so that its words are the same from every front end.
template <class T, class Set>
CLI::Validator library_check(Set set) {
    return CLI::Validator(
        [set](std::string& text) -> std::string {
            T value{};
            if (!CLI::detail::lexical_cast(text, value))
                return std::string(std::is_integral_v<T> ? "must be a whole number" : "must be a number") + ", not '" +
                       text + "'";
            RenderOptions probe;
            set(probe, value);
            try {
                check_render_options(probe);
            } catch (const Error& e) {
                return e.message();
            }
            return {};
        },
        "");
}

// A named option's value read by the library's own function (`read`, e.g.
// integrator_option), whose message CLI11 reports for a name it refuses.
template <class Read>
CLI::Validator library_name_check(Read read) {
    return CLI::Validator(
        [read](std::string& text) -> std::string {
            try {
                read(text);
            } catch (const Error& e) {
                return e.message();
            }
            return {};
        },
        "");
}

// --exposure and --tonemap: how 8-bit outputs (PNG, JPEG) show radiance (spec §1, §27).
void add_display_options(CLI::App& command, CliOptions& o) {
    command.add_option("--exposure", o.display.exposure, "Multiply radiance by 2^E before 8-bit encoding (PNG, JPEG)")
        ->check(CLI::Number)
        ->capture_default_str();
    command
        .add_option_function<std::string>(
            "--tonemap", [&o](const std::string& name) { o.display.tonemap = tonemap_option(name); },
            "8-bit outputs: none (clamp to [0, 1], the default) or pbr-neutral (Khronos PBR Neutral, after the "
            "exposure)")
        ->check(library_name_check(tonemap_option));
}

// The options of §1 that decide what is rendered; `render` and `explain` share them.
void add_render_options(CLI::App& command, CliOptions& o) {
    RenderOptions& r = o.render;
    command
        .add_option("--frame", r.frame,
                    "Frame F of an animated scene (time F / fps, spec §22), 0 to " + std::to_string(kMaxFrame))
        ->check(library_check<std::int64_t>([](RenderOptions& p, std::int64_t v) { p.frame = v; }));
    command.add_option("--width", r.overrides.width, "Image width in pixels (overrides the scene)");
    command.add_option("--height", r.overrides.height, "Image height in pixels (overrides the scene)");
    command.add_option("--spp", r.overrides.spp, "Samples per pixel (overrides the scene)");
    command.add_option("--seed", r.overrides.seed, "Random seed, a non-negative integer (overrides the scene)")
        ->check(CLI::NonNegativeNumber);
    command
        .add_option("--threads", r.threads,
                    "Worker threads, 0 to " + std::to_string(kMaxThreads) + "; 0 = all hardware threads")
        ->check(library_check<int>([](RenderOptions& p, int v) { p.threads = v; }))
        ->capture_default_str();
    add_display_options(command, o);
    command
        .add_option_function<std::string>(
            "--accel", [&r](const std::string& name) { r.accel = accel_option(name); },
            "Acceleration structure: " + accel_names())
        ->check(library_name_check(accel_option))
        ->default_str(std::string(accel_name(r.accel)));
    command
        .add_option_function<std::string>(
            "--integrator", [&r](const std::string& name) { r.overrides.integrator = integrator_option(name); },
            "direct (point lights, spec §4) or path (path tracing; overrides the scene)")
        ->check(library_name_check(integrator_option));
    command
        .add_option("--max-depth", r.overrides.max_depth,
                    "Most scattering events on a path, 0 to 1024 (path; overrides the scene)")
        ->check(library_check<int>([](RenderOptions& p, int v) { p.overrides.max_depth = v; }));
    command
        .add_option("--max-volume-depth", r.overrides.max_volume_depth,
                    "Most scattering events in media on a path, 0 to 65536 (path; default 256; overrides the scene)")
        ->check(library_check<int>([](RenderOptions& p, int v) { p.overrides.max_volume_depth = v; }));
    command
        .add_option_function<std::string>(
            "--light-tree", [&r](const std::string& name) { r.light_selection = light_selection_option(name); },
            "Choose emitters by a light tree: auto (from 8 emitters on), on, or off (in proportion to power)")
        ->check(library_name_check(light_selection_option))
        ->default_str(std::string(light_selection_name(r.light_selection)));
    command
        .add_option_function<std::string>(
            "--texture-filter",
            [&r](const std::string& name) { r.overrides.texture_filter = texture_filter_option(name); },
            "Texture lookups: bilinear (full resolution, the default) or mipmap (by the ray's footprint; "
            "overrides the scene)")
        ->check(library_name_check(texture_filter_option));
    command.add_flag("-q,--quiet", o.quiet, "No progress bar, no summary");
}

// The render outputs of spec §18: time budget, adaptive sampling, AOVs.
void add_output_options(CLI::App* render_command, CliOptions& o) {
    CLI::App& render = *render_command;
    RenderOptions& r = o.render;
    render
        .add_option("--time", r.time_budget,
                    "Render passes until the next would end past SECONDS after the start (at least one pass)")
        ->check(library_check<double>([](RenderOptions& p, double v) { p.time_budget = v; }));
    render
        .add_option("--noise-threshold", r.noise_threshold,
                    "Adaptive sampling: a pixel stops once the standard error of its mean luminance is at most "
                    "T times that mean")
        ->check(library_check<double>([](RenderOptions& p, double v) { p.noise_threshold = v; }));
    render
        .add_option("--min-spp", r.min_spp,
                    "Adaptive sampling: samples every pixel takes before it may stop, 1 to " + std::to_string(kMaxSpp))
        ->check(library_check<int>([](RenderOptions& p, int v) { p.min_spp = v; }))
        ->capture_default_str();
    render
        .add_option_function<std::string>(
            "--aov", [&r](const std::string& list) { r.aovs = aov_option(list); },
            "Float layers added to an .exr output: any of albedo, normal, depth, position, spp, variance, "
            "noisy (with --denoise), denoise (the denoiser's inputs), comma-separated")
        ->check(library_name_check(aov_option));
    render
        .add_option_function<std::vector<int>>(
            "--crop",
            [&r](const std::vector<int>& v) {
                if (v[0] < 0 || v[1] < 0 || v[2] <= v[0] || v[3] <= v[1])
                    throw CLI::ValidationError("--crop",
                                               "expected X0 Y0 X1 Y1 with 0 <= X0 < X1 and 0 <= Y0 < Y1, not " +
                                                   std::to_string(v[0]) + " " + std::to_string(v[1]) + " " +
                                                   std::to_string(v[2]) + " " + std::to_string(v[3]));
                r.crop = PixelWindow{v[0], v[1], v[2] - v[0], v[3] - v[1]};
            },
            "Render only the pixels X0 <= x < X1, Y0 <= y < Y1 and write an image of that size, each pixel as in "
            "the whole render")
        ->expected(4);
    render.add_flag("--denoise", r.denoise,
                    "Denoise the image once the last pass is done (at least 2 spp; the --time budget includes it)");
    render
        .add_option("--display-server", o.display_server,
                    "Stream the image as it refines to the tev viewer listening at HOST:PORT (e.g. 127.0.0.1:14158)")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                return parse_display_address(text) ? "" : "expected HOST:PORT (or [IPV6]:PORT), port 1-65535";
            },
            "HOST:PORT"));
    render.add_option_function<std::string>(
        "--shard",
        [&o](const std::string& text) {
            const auto slash = text.find('/');
            int index = -1, count = 0;
            const bool parsed = slash != std::string::npos &&
                                std::from_chars(text.data(), text.data() + slash, index).ptr == text.data() + slash &&
                                std::from_chars(text.data() + slash + 1, text.data() + text.size(), count).ptr ==
                                    text.data() + text.size();
            if (!parsed || count < 1 || count > kMaxShards || index < 0 || index >= count)
                throw CLI::ValidationError("--shard", "expected I/N with 0 <= I < N <= " + std::to_string(kMaxShards) +
                                                          ", not '" + text + "'");
            o.shard_index = index;
            o.shard_count = count;
            o.sharded = true;
        },
        "Render share I of N of the pixels into an .exr that 'sombra merge' joins with the others (with --frames: "
        "every Nth frame, from the first plus I)");
    // Frames are whole numbers from 0 up: "A-B" stays unambiguous.
    render.add_option_function<std::string>(
        "--frames",
        [&o](const std::string& text) {
            const auto dash = text.find('-');
            std::int64_t first = -1, last = -1;
            const bool parsed = dash != std::string::npos && dash > 0 &&
                                std::from_chars(text.data(), text.data() + dash, first).ptr == text.data() + dash &&
                                std::from_chars(text.data() + dash + 1, text.data() + text.size(), last).ptr ==
                                    text.data() + text.size();
            if (!parsed || first < 0 || last < first || last > kMaxFrame || last - first >= kMaxFrameCount)
                throw CLI::ValidationError("--frames", "expected A-B with 0 <= A <= B and at most " +
                                                           std::to_string(kMaxFrameCount) + " frames, not '" + text +
                                                           "'");
            o.first_frame = first;
            o.last_frame = last;
        },
        "Render frames A to B into the output name with '#'s replaced by the frame number (out_####.png)");
}

}  // namespace

namespace {

// parse_command_line, printing help and version to `out` and errors to `err`.
CliParse parse(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    CLI::App app{"sombra: a ray tracer that is right to the last pixel", "sombra"};
    // The contract version it implements, e.g. "sombra 2.0.0 (scene format version 2)".
    app.set_version_flag("--version", std::string("sombra ") + SOMBRA_VERSION + " (scene format version " +
                                          SOMBRA_SCENE_FORMAT_VERSION + ")");
    app.require_subcommand(1);

    CliOptions o;
    CLI::App* render = app.add_subcommand(
        "render", "Render a scene (.json) or take a quick look at a model (.obj, .ply, .gltf, .glb)");
    render->add_option("input", o.input, "Scene file (.json) or model (.obj, .ply, .gltf, .glb)")->required();
    render->add_option("-o,--output", o.output, "Image to write: .png or .jpg (8-bit sRGB), .pfm or .exr (linear)")
        ->capture_default_str();
    add_render_options(*render, o);
    render->add_option("--stats-json", o.stats_json, "Write the run's statistics as JSON to FILE");
    add_output_options(render, o);

    CLI::App* explain = app.add_subcommand(
        "explain", "Tell the story of one pixel: every term of the rendering equation behind its value");
    explain->add_option("input", o.input, "Scene file (.json) or model (.obj, .ply, .gltf, .glb)")->required();
    explain->add_option("x", o.pixel_x, "Pixel column, 0 at the left")->required();
    explain->add_option("y", o.pixel_y, "Pixel row, 0 at the top")->required();
    explain->add_option("--sample", o.sample, "Which of the pixel's samples, 0 to spp - 1")->capture_default_str();
    explain->add_flag("--json", o.json, "Print the story as one JSON object");
    explain->add_option("--svg", o.svg, "Also draw the story (the path in the scene, beside the render) into FILE");
    explain->add_flag("--denoise", o.render.denoise,
                      "Also the pixel denoised, and the weights the denoiser gave its neighbours (renders the image)");
    add_render_options(*explain, o);

    CLI::App* view = app.add_subcommand(
        "view", "Serve the render on 127.0.0.1 to a browser: it refines live, the camera moves, pixels explain");
    view->add_option("input", o.input, "Scene file (.json) or model (.obj, .ply, .gltf, .glb)")->required();
    view->add_option("--port", o.port, "Port on 127.0.0.1 to listen on; 0 = a free one")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    view->add_flag("--denoise", o.render.denoise,
                   "Start with the denoise switch on: the newest finished pass shown denoised (at least 2 spp)");
    add_render_options(*view, o);

    CLI::App* merge =
        app.add_subcommand("merge", "Join the .exr shards of one render (sombra render --shard I/N) into its image");
    merge->add_option("parts", o.parts, "The N shards, each an .exr written with --shard I/N")->required();
    merge->add_option("-o,--output", o.output, "Image to write: .png or .jpg (8-bit sRGB), .pfm or .exr (linear)")
        ->capture_default_str();
    add_display_options(*merge, o);
    merge->add_flag("--denoise", o.render.denoise,
                    "Denoise the merged image (shards rendered with --denoise carry what it needs)");
    merge->add_flag("-q,--quiet", o.quiet, "No summary line");

    CLI::App* denoise = app.add_subcommand(
        "denoise", "Denoise an .exr written with --aov denoise (or merged from such shards), as render --denoise does");
    denoise->add_option("input", o.input, "An .exr with the denoiser's layers (sombra render --aov denoise)")
        ->required();
    denoise->add_option("-o,--output", o.output, "Image to write: .png or .jpg (8-bit sRGB), .pfm or .exr (linear)")
        ->capture_default_str();
    add_display_options(*denoise, o);
    denoise
        ->add_option("--threads", o.render.threads,
                     "Worker threads, 0 to " + std::to_string(kMaxThreads) + "; 0 = all hardware threads")
        ->check(library_check<int>([](RenderOptions& p, int v) { p.threads = v; }))
        ->capture_default_str();
    denoise->add_flag("-q,--quiet", o.quiet, "No summary line");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        out << app.help();
        return {std::nullopt, 0};
    } catch (const CLI::CallForAllHelp&) {
        out << app.help("", CLI::AppFormatMode::All);
        return {std::nullopt, 0};
    } catch (const CLI::CallForVersion& e) {
        out << e.what() << '\n';
        return {std::nullopt, 0};
    } catch (const CLI::ParseError& e) {
        const std::string_view sub = argc > 1 ? std::string_view(argv[1]) : std::string_view();
        err << "sombra: error: command line: " << parse_error_hint(app, argc, argv).value_or(one_line(e.what()))
            << " (see 'sombra "
            << (sub == "explain" || sub == "view" || sub == "merge" || sub == "denoise" ? sub : "render")
            << " --help')\n";
        return {std::nullopt, 2};
    }
    o.command = app.got_subcommand(explain)   ? Command::Explain
                : app.got_subcommand(view)    ? Command::View
                : app.got_subcommand(merge)   ? Command::Merge
                : app.got_subcommand(denoise) ? Command::Denoise
                                              : Command::Render;
    const char* const subcommand = o.command == Command::Explain   ? "explain"
                                   : o.command == Command::View    ? "view"
                                   : o.command == Command::Merge   ? "merge"
                                   : o.command == Command::Denoise ? "denoise"
                                                                   : "render";
    const auto refuse = [&err, subcommand](const std::string& problem) {
        err << "sombra: error: command line: " << problem << " (see 'sombra " << subcommand << " --help')\n";
        return CliParse{std::nullopt, 2};
    };
    if (o.render.frame && o.first_frame) return refuse("give --frame or --frames, not both");
    if (o.render.crop && !o.display_server.empty())
        return refuse("--crop and --display-server cannot go together yet: tev is sent the whole image's size");
    if (o.render.aovs.noisy && !o.render.denoise)
        return refuse("--aov noisy is the image before denoising: it needs --denoise");
    if (o.render.denoise && o.render.overrides.spp && *o.render.overrides.spp < 2)
        return refuse("--denoise needs at least 2 samples per pixel, not --spp " +
                      std::to_string(*o.render.overrides.spp));
    if (o.first_frame && o.output.find('#') == std::string::npos)
        return refuse("--frames needs '#' in the output name (out_####.png): each frame's number replaces them");
    if (o.first_frame && o.render.time_budget)
        return refuse("--frames and --time cannot go together: the budget is for one image");
    // With --frames, --shard splits the frames, and each is a whole image in any format.
    if (o.sharded && !o.first_frame) {
        const char* problem = nullptr;
        if (std::filesystem::path(o.output).extension() != ".exr")
            problem = "--shard writes an .exr (the shard's float pixels and what merging needs)";
        else if (o.render.noise_threshold)
            problem =
                "--shard and --noise-threshold cannot go together: a pixel's stopping reads its neighbours, "
                "which another shard renders";
        if (problem) {
            err << "sombra: error: command line: " << problem << " (see 'sombra render --help')\n";
            return {std::nullopt, 2};
        }
    }
    if (o.display.tonemap != Tonemap::None &&
        (o.command == Command::Render || o.command == Command::Merge || o.command == Command::Denoise)) {
        bool eight_bit = false;
        try {
            eight_bit = is_eight_bit(image_format_for(o.output));
        } catch (const Error&) {
            eight_bit = true;  // an unknown extension is the output's own error, told after parsing
        }
        if (!eight_bit)
            return refuse("--tonemap applies to 8-bit outputs (.png, .jpg); '" + one_line(o.output) +
                          "' keeps linear radiance");
    }
    if (o.render.aovs.any()) {
        std::string ext = std::filesystem::path(o.output).extension().string();
        for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (ext != ".exr") {
            err << "sombra: error: command line: --aov needs an .exr output, not '" << one_line(o.output)
                << "' (see 'sombra render --help')\n";
            return {std::nullopt, 2};
        }
    }
    return {o, 0};
}

}  // namespace

std::string frame_file_name(const std::string& output, std::int64_t frame) {
    const std::string digits = std::to_string(frame < 0 ? -frame : frame);
    std::string out;
    for (std::size_t i = 0; i < output.size();) {
        if (output[i] != '#') {
            out += output[i++];
            continue;
        }
        std::size_t run = 0;
        while (i < output.size() && output[i] == '#') ++i, ++run;
        if (frame < 0) out += '-';
        if (digits.size() < run) out.append(run - digits.size(), '0');
        out += digits;
    }
    return out;
}

CliParse parse_command_line(int argc, const char* const* argv) { return parse(argc, argv, std::cout, std::cerr); }

}  // namespace sombra
