// sombra-bench: how fast sombra's BVH is next to Embree, how fast its OBJ
// loader is next to tinyobjloader, and how the costs grow with the mesh.
// Tables go to stdout (Markdown), progress to stderr; tools/bench.sh runs
// all three and writes docs/performance.md.
#include <CLI/CLI.hpp>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "denoise_bench.h"
#include "growth_bench.h"
#include "load_bench.h"
#include "path_bench.h"
#include "rays_bench.h"
#include "scene_bench.h"
#include "tree_bench.h"

namespace {

void add_embree_quality_option(CLI::App& command, sombra::bench::EmbreeSettings& embree) {
    using sombra::bench::EmbreeQuality;
    const std::map<std::string, EmbreeQuality> names{{"medium", EmbreeQuality::Medium}, {"high", EmbreeQuality::High}};
    command
        .add_option("--embree-quality", embree.quality,
                    "Embree's build quality: medium (its default) or high (spatial splits)")
        ->transform(CLI::CheckedTransformer(names));
}

}  // namespace

int main(int argc, char** argv) {
    using namespace sombra::bench;
    CLI::App app{"sombra-bench: sombra's BVH against Embree, its OBJ loader against tinyobjloader, cost growth",
                 "sombra-bench"};
    app.require_subcommand(1);

    SceneBenchOptions scene_options;
    std::vector<std::string> scene_files;
    CLI::App* scenes = app.add_subcommand("scenes", "Render scenes with every backend (bvh, embree), alternating");
    scenes->add_option("scene", scene_files, "Scene files (.json)")->required()->check(CLI::ExistingFile);
    scenes->add_option("--reps", scene_options.reps, "Timed rounds per backend (median reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    scenes->add_option("--width", scene_options.width, "Image width (overrides the scenes)");
    scenes->add_option("--height", scene_options.height, "Image height (overrides the scenes)");
    add_embree_quality_option(*scenes, scene_options.embree);

    int load_reps = 5;
    std::string obj_file;
    CLI::App* load = app.add_subcommand(
        "load", "Load an OBJ with sombra and with tinyobjloader, alternating (a .gltf/.glb: with tinygltf)");
    load->add_option("obj", obj_file, "OBJ, glTF or GLB file")->required()->check(CLI::ExistingFile);
    load->add_option("--reps", load_reps, "Timed rounds per loader (median reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();

    GrowthOptions growth_options;
    std::vector<std::string> model_files;
    CLI::App* growth = app.add_subcommand("growth", "Build and render cost against triangle count (quick-look view)");
    growth->add_option("model", model_files, "Meshes (.obj, .ply), smallest first")
        ->required()
        ->check(CLI::ExistingFile);
    growth->add_option("--reps", growth_options.reps, "Timed rounds per backend (median reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    growth->add_option("--width", growth_options.width, "Image width")->capture_default_str();
    growth->add_option("--height", growth_options.height, "Image height")->capture_default_str();
    growth->add_option("--csv", growth_options.csv, "Also write the numbers as CSV to this file");
    add_embree_quality_option(*growth, growth_options.embree);

    PathBenchOptions path_options;
    std::vector<std::string> path_files;
    CLI::App* path = app.add_subcommand("path", "Path-trace scenes with every backend (bvh, embree), alternating");
    path->add_option("scene", path_files, "Scene files (.json); rendered with integrator = path")
        ->required()
        ->check(CLI::ExistingFile);
    path->add_option("--reps", path_options.reps, "Timed renders per backend (median reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    path->add_option("--width", path_options.width, "Image width")->check(CLI::Range(1, 4096))->capture_default_str();
    path->add_option("--height", path_options.height, "Image height")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    path->add_option("--spp", path_options.spp, "Samples per pixel")
        ->check(CLI::Range(1, 65536))
        ->capture_default_str();
    path->add_option("--max-depth", path_options.max_depth, "Most scattering events on a path")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    add_embree_quality_option(*path, path_options.embree);

    RaysBenchOptions rays_options;
    std::vector<std::string> rays_files;
    CLI::App* rays = app.add_subcommand(
        "rays", "Trace batches of incoherent rays from the surfaces with every backend: traversal alone");
    rays->add_option("scene", rays_files, "Scene files (.json)")->required()->check(CLI::ExistingFile);
    rays->add_option("--reps", rays_options.reps, "Timed rounds per backend (median reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    rays->add_option("--rays", rays_options.rays, "Rays of each kind (closest hit, shadow)")
        ->check(CLI::Range(1, 100000000))
        ->capture_default_str();
    add_embree_quality_option(*rays, rays_options.embree);
    // Only here: rendering with it, Embree's robust mode finds the surface a
    // spawned ray leaves at t = 0, and the other benchmarks' checks stop.
    rays->add_flag("--embree-robust", rays_options.embree.robust,
                   "Run Embree in its robust mode (RTC_SCENE_FLAG_ROBUST), which like sombra's BVH lets no ray "
                   "through an edge");

    int tree_reps = 5;
    std::vector<std::string> tree_files;
    CLI::App* tree = app.add_subcommand("tree", "The BVH's tree on scenes: SAH cost, size, build time");
    tree->add_option("scene", tree_files, "Scene files (.json)")->required()->check(CLI::ExistingFile);
    tree->add_option("--reps", tree_reps, "Timed builds (median reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();

    int denoise_reps = 3;
    std::vector<int> denoise_threads{1, 2};
    std::string denoise_file;
    CLI::App* denoise = app.add_subcommand("denoise", "The denoiser's time per megapixel, stage by stage");
    denoise->add_option("layers", denoise_file, "An .exr written with sombra render --aov denoise")
        ->required()
        ->check(CLI::ExistingFile);
    denoise->add_option("--threads", denoise_threads, "Thread counts to measure")
        ->delimiter(',')
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    denoise->add_option("--reps", denoise_reps, "Timed runs (median reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();

    PathErrorOptions error_options;
    std::string error_file;
    std::string cache_dir = error_options.cache_dir.string();
    CLI::App* path_error = app.add_subcommand(
        "path-error", "Path tracing's error against a converged reference, at fixed spp and at equal time");
    path_error->add_option("scene", error_file, "Scene file (.json)")->required()->check(CLI::ExistingFile);
    path_error->add_option("--width", error_options.width, "Image width")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    path_error->add_option("--height", error_options.height, "Image height")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    path_error->add_option("--max-depth", error_options.max_depth, "Most scattering events on a path")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    path_error->add_option("--reference-spp", error_options.reference_spp, "Samples per pixel of the reference")
        ->check(CLI::Range(1, 65536))
        ->capture_default_str();
    path_error->add_option("--spp", error_options.fixed_spp, "Fixed sample counts to measure")
        ->delimiter(',')
        ->check(CLI::Range(1, 65536))
        ->capture_default_str();
    path_error->add_option("--budget", error_options.budget_seconds, "Seconds for the equal-time render")
        ->check(CLI::Range(0.001, 3600.0))
        ->capture_default_str();
    path_error
        ->add_option("--noise-threshold", error_options.noise_thresholds,
                     "Adaptive renders at these thresholds (up to the largest --spp)")
        ->delimiter(',');
    path_error->add_option("--cache-dir", cache_dir, "Where the reference image is cached")->capture_default_str();

    CLI11_PARSE(app, argc, argv);
    error_options.cache_dir = cache_dir;
    try {
        if (*scenes) run_scene_bench(scene_files, scene_options, std::cout);
        if (*load) {
            const std::string ext = std::filesystem::path(obj_file).extension().string();
            if (ext == ".gltf" || ext == ".glb")
                run_gltf_load_bench(obj_file, load_reps, std::cout);
            else
                run_load_bench(obj_file, load_reps, std::cout);
        }
        if (*growth) run_growth_bench(model_files, growth_options, std::cout);
        if (*path) run_path_bench(path_files, path_options, std::cout);
        if (*rays) run_rays_bench(rays_files, rays_options, std::cout);
        if (*tree) run_tree_bench(tree_files, tree_reps, std::cout);
        if (*path_error) run_path_error_bench(error_file, error_options, std::cout);
        if (*denoise) run_denoise_bench(denoise_file, denoise_threads, denoise_reps, std::cout);
    } catch (const sombra::Error& e) {
        std::cerr << "sombra-bench: error: " << e.what() << '\n';
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "sombra-bench: error: out of memory\n";
        return 1;
    }
    return 0;
}
