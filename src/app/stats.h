// The run's statistics of spec §6: what --stats-json writes and what the
// summary line says.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace sombra {

struct RunStats {
    std::uint64_t triangles = 0;            // stored (spec §23)
    std::uint64_t instanced_triangles = 0;  // drawn: equal to triangles without instances
    std::uint64_t frames = 1;               // images rendered (spec §22: --frames)
    int width = 0, height = 0;
    int spp = 0;  // asked for; under --time without --spp, the most a pixel took
    // Spec §18: the mean samples a pixel took (integral when all took the
    // same), and the passes rendered.
    double spp_reached = 0;
    bool spp_uniform = true;
    int passes = 0;
    int threads = 0;    // worker threads actually used
    int processes = 1;  // MPI ranks (mpirun -np K, spec §21); rays are counted over all of them
    std::string accel;
    std::string integrator;  // "direct" or "path"
    int max_depth = 0;
    std::string texture_filter;  // "bilinear" or "mipmap"
    std::size_t accel_bytes = 0;
    double load_seconds = 0;    // parsing the scene and mesh files
    double build_seconds = 0;   // building the acceleration structure
    double mipmap_seconds = 0;  // building the textures' mip pyramids (0 unless --texture-filter mipmap)
    double render_seconds = 0;
    double denoise_seconds = 0;  // spec §25's denoiser (0 without --denoise)
    double write_seconds = 0;
    double total_seconds = 0;
    std::uint64_t camera_rays = 0;
    std::uint64_t shadow_rays = 0;  // every next-event ray (point lights, and under path sampled lights)
    std::uint64_t bounce_rays = 0;  // rays traced by BSDF sampling
    std::uint64_t nonfinite_samples = 0;
    std::uint64_t peak_rss_bytes = 0;
};

// Writes the statistics as one JSON object, atomically (temporary file, then
// rename); throws Error(path, ...) on failure.
void write_stats_json(const std::filesystem::path& path, const RunStats& stats);

// One line for the terminal, e.g. "sombra: 69,453 triangles, 1280x720 at 1 spp, direct |
// load 0.21 s, build 0.03 s, render 0.52 s (4.6 Mrays/s, 2 threads), write 0.05 s | wrote out.png".
std::string summary_line(const RunStats& stats, const std::string& output);

}  // namespace sombra
