#include "app/prepare.h"

#include <cctype>
#include <iostream>

#include "core/error.h"
#include "io/quicklook.h"
#include "io/scene_json/scene_file.h"
#include "scene/texture_mipmap.h"

namespace sombra {

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void check_side_file_path(const std::filesystem::path& path) {
    const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec))
        throw Error(path.string(), "folder '" + folder.string() + "' does not exist");
    if (std::filesystem::is_directory(path, ec)) throw Error(path.string(), "is a folder");
}

std::string one_line(std::string text) {
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text;
}

LoadedScene load_input(const std::filesystem::path& input, Diagnostics& diag) {
    const std::string ext = lower_extension(input);
    if (ext == ".json") return load_scene_file(input, diag);
    if (ext == ".obj" || ext == ".ply" || ext == ".gltf" || ext == ".glb") return make_quicklook_scene(input, diag);
    throw Error(input.string(),
                "unknown input type '" + ext + "' (expected a scene .json, or a model .obj, .ply, .gltf or .glb)");
}

RenderSettings resolve_settings(const RenderSettings& scene_settings, const CliOptions& o) {
    RenderSettings s = scene_settings;
    auto check = [&s](const char* option) {
        if (const std::string problem = render_settings_problem(s); !problem.empty()) throw Error(option, problem);
    };
    if (o.width) {
        s.width = *o.width;
        check("--width");
    }
    if (o.height) {
        s.height = *o.height;
        check("--height");
    }
    if (o.spp) {
        s.spp = *o.spp;
        check("--spp");
    }
    if (o.seed) s.seed = *o.seed;
    if (o.integrator) s.integrator = *o.integrator == "path" ? IntegratorKind::Path : IntegratorKind::Direct;
    if (o.max_depth) {
        s.max_depth = *o.max_depth;
        check("--max-depth");
    }
    if (o.texture_filter)
        s.texture_filter = *o.texture_filter == "mipmap" ? TextureFilter::Mipmap : TextureFilter::Bilinear;
    return s;
}

RenderSettings resolve_render_settings(const RenderSettings& scene_settings, const CliOptions& o) {
    RenderSettings s = resolve_settings(scene_settings, o);
    if (o.time_budget && !o.spp) s.spp = kMaxSpp;
    return s;
}

SamplingLimits sampling_limits(const CliOptions& o, std::chrono::steady_clock::time_point start) {
    SamplingLimits limits;
    if (o.time_budget)
        limits.deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(*o.time_budget));
    if (o.noise_threshold) limits.noise_threshold = *o.noise_threshold;
    limits.min_spp = o.min_spp;
    return limits;
}

void check_explain_pixel(const CliOptions& o, const RenderSettings& s) {
    const std::string where = "pixel (" + std::to_string(o.pixel_x) + ", " + std::to_string(o.pixel_y) + ")";
    if (o.pixel_x < 0 || o.pixel_x >= s.width || o.pixel_y < 0 || o.pixel_y >= s.height)
        throw Error(where, "outside the " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                               " image (columns 0 to " + std::to_string(s.width - 1) + ", rows 0 to " +
                               std::to_string(s.height - 1) + ")");
    if (o.sample < 0 || o.sample >= s.spp)
        throw Error("--sample", "sample " + std::to_string(o.sample) + " does not exist: the pixel has " +
                                    std::to_string(s.spp) + " sample" + (s.spp == 1 ? "" : "s") + " (0 to " +
                                    std::to_string(s.spp - 1) + ")");
}

void prepare_textures(Scene& scene, const RenderSettings& settings) {
    if (settings.texture_filter == TextureFilter::Mipmap) build_mip_pyramids(scene.textures);
}

double frame_time(const Scene& scene, std::int64_t frame) {
    return static_cast<double>(frame) / (scene.animation ? scene.animation->fps : 24.0);
}

void move_to_frame(Scene& scene, const CliOptions& options) {
    if (!scene.animation) return;
    set_scene_time(scene, frame_time(scene, options.frame.value_or(scene.animation->first_frame)), options.input);
}

LightSelection light_selection(const CliOptions& o) {
    return o.light_tree == "on"    ? LightSelection::Tree
           : o.light_tree == "off" ? LightSelection::Power
                                   : LightSelection::Automatic;
}

void print_warnings(const Diagnostics& diag, const Scene& scene, const RenderSettings& settings, const CliOptions& o) {
    for (const std::string& w : diag.warnings) std::cerr << "sombra: warning: " << one_line(w) << '\n';
    // After the overrides: --integrator path silences it, --integrator direct may cause it.
    if (settings.integrator == IntegratorKind::Direct && needs_path_integrator(scene))
        std::cerr << "sombra: warning: " << one_line(o.input)
                  << ": the direct integrator lights with point, spot and directional lights only: quad lights "
                     "and the environment are only seen, mirror and glass reflect nothing from them; use "
                     "--integrator path\n";
}

}  // namespace sombra
