// Small helpers shared by the benchmarks: timing, medians, number formatting,
// Markdown tables, and the image check that runs before any timing.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "core/format.h"
#include "core/peak_rss.h"
#include "render/film.h"

namespace sombra::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// The median of the values (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values);

// `value` with `digits` digits after the point, e.g. fixed(0.1234, 3) = "0.123".
std::string fixed(double value, int digits);
// Seconds with three significant digits at least (0.00123, 0.0456, 1.23, 12.3).
std::string seconds(double s);
// a / b as "1.23" (two decimals), or "–" when b is zero.
std::string ratio(double a, double b);

// A Markdown table; columns listed in `right` are right-aligned (numbers).
struct Table {
    std::vector<std::string> header;
    std::vector<bool> right;
    std::vector<std::vector<std::string>> rows;
};
std::string to_markdown(const Table& table);

// The backends the benchmarks compare: bvh first, then embree when built in.
std::vector<AccelKind> compared_accels();

// How Embree builds in the benchmarks (--embree-quality): at its default
// RTC_BUILD_QUALITY_MEDIUM, or at HIGH (its spatial-split builder), the
// yardstick issue 10's render target names.
enum class EmbreeQuality { Medium, High };

// How the benchmarks run Embree: its build quality, and (`rays
// --embree-robust`) whether with RTC_SCENE_FLAG_ROBUST, the mode that trades
// speed for rays not slipping through edges: the fairer yardstick for
// sombra's BVH, whose box and triangle tests are conservative and
// watertight. (Not for renders: that mode reports the surface a spawned ray
// leaves at t = 0, docs/performance.md.)
struct EmbreeSettings {
    EmbreeQuality quality = EmbreeQuality::Medium;
    bool robust = false;
};

// What make_accel(scene, kind) builds, but Embree as `embree` says.
Accel make_compared_accel(const Scene& scene, AccelKind kind, const EmbreeSettings& embree);
// accel_name(kind), with " high" for Embree at High and " robust" for its
// robust mode.
std::string accel_label(AccelKind kind, const EmbreeSettings& embree);

// Pixel-by-pixel agreement of two films of the same size. Two pixels agree
// when every channel does to 1e-3 relative (below what an 8-bit PNG shows,
// above the rounding of a slightly different t or barycentric).
struct ImageAgreement {
    std::size_t pixels = 0;
    std::size_t equal = 0;
    double fraction() const { return pixels == 0 ? 1.0 : double(equal) / double(pixels); }
};
ImageAgreement compare_films(const Film& a, const Film& b);
// Whether two RGB pixels agree as compare_films counts them.
bool same_colour(const float* a, const float* b);

// The benchmark refuses to time backends whose images agree in fewer pixels.
inline constexpr double kMinEqualFraction = 0.999;

// The BVH against the brute-force loop, before any timing: radiance(accel,
// i, j) traces pixel (i, j) with `accel` (everything else the same) at the
// centres of every stride-th pixel: every 37th, fewer on big scenes so that
// brute force spends at most about 2·10⁹ triangle tests (a pixel costing
// `rays_per_pixel` rays), but never fewer than `min_pixels`. The BVH's hits
// are bit-identical to brute's, so the pixels must agree.
ImageAgreement bvh_against_brute(const TriangleMesh& mesh, const Accel& bvh, int width, int height,
                                 double rays_per_pixel, std::size_t min_pixels,
                                 const std::function<Vec3(const Accel& accel, int i, int j)>& radiance);

}  // namespace sombra::bench
