#include "app/stats.h"

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/format.h"
#include "image/atomic_file.h"

namespace sombra {

void write_stats_json(const std::filesystem::path& path, const RunStats& s) {
    const nlohmann::ordered_json j = {
        {"triangles", s.triangles},
        {"instanced_triangles", s.instanced_triangles},
        {"frames", s.frames},
        {"width", s.width},
        {"height", s.height},
        {"spp", s.spp},
        {"spp_reached", s.spp_uniform ? nlohmann::ordered_json(static_cast<std::uint64_t>(s.spp_reached))
                                      : nlohmann::ordered_json(s.spp_reached)},
        {"passes", s.passes},
        {"threads", s.threads},
        {"processes", s.processes},
        {"accel", s.accel},
        {"integrator", s.integrator},
        {"max_depth", s.max_depth},
        {"texture_filter", s.texture_filter},
        {"accel_bytes", s.accel_bytes},
        {"load_seconds", s.load_seconds},
        {"build_seconds", s.build_seconds},
        {"mipmap_seconds", s.mipmap_seconds},
        {"render_seconds", s.render_seconds},
        {"denoise_seconds", s.denoise_seconds},
        {"write_seconds", s.write_seconds},
        {"total_seconds", s.total_seconds},
        {"camera_rays", s.camera_rays},
        {"shadow_rays", s.shadow_rays},
        {"bounce_rays", s.bounce_rays},
        {"nonfinite_samples", s.nonfinite_samples},
        {"peak_rss_bytes", s.peak_rss_bytes},
    };
    const std::string text = j.dump(2) + "\n";
    write_file_atomically(path, [&text](const std::filesystem::path& temp) {
        std::ofstream out(temp, std::ios::binary);
        out << text;
        out.close();
        if (!out) throw std::runtime_error(errno_message(errno));
    });
}

namespace {

std::string seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f s", s);
    return buf;
}

}  // namespace

// "16 spp", or "12.4 spp (adaptive, at most 64)" when pixels took different counts.
std::string samples_text(const RunStats& s) {
    if (s.spp_uniform) return std::to_string(static_cast<std::uint64_t>(s.spp_reached)) + " spp";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f spp (adaptive, at most %d)", s.spp_reached, s.spp);
    return buf;
}

std::string summary_line(const RunStats& s, const std::string& output) {
    const double rays = static_cast<double>(s.camera_rays + s.shadow_rays + s.bounce_rays);
    const double mrays = s.render_seconds > 0 ? rays / s.render_seconds * 1e-6 : 0.0;
    char rate[48];
    std::snprintf(rate, sizeof rate, "%.1f Mrays/s", mrays);
    return "sombra: " + thousands(s.triangles) + " triangles, " + std::to_string(s.width) + "x" +
           std::to_string(s.height) + (s.frames > 1 ? " × " + std::to_string(s.frames) + " frames" : std::string()) +
           " at " + samples_text(s) + (s.passes > 1 ? " in " + std::to_string(s.passes) + " passes" : std::string()) +
           ", " + s.integrator + " | load " + seconds(s.load_seconds) + ", build " + seconds(s.build_seconds) +
           ", render " + seconds(s.render_seconds) + " (" + rate + ", " +
           (s.processes > 1 ? std::to_string(s.processes) + " processes × " : std::string()) +
           std::to_string(s.threads) + (s.threads == 1 ? " thread" : " threads") +
           (s.processes > 1 ? " each), " : "), ") +
           (s.denoise_seconds > 0 ? "denoise " + seconds(s.denoise_seconds) + ", " : std::string()) + "write " +
           seconds(s.write_seconds) + " | wrote " + output;
}

}  // namespace sombra
