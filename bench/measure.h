// One scene through every compared backend: first an untimed render each,
// whose images must agree (as tinybvh's speed test checks its result before
// it reports a number), then `reps` timed rounds of build + render, the
// backends alternating (bvh, embree; then embree, bvh; ...) so that drift in
// the machine's speed hits both alike.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "bench_util.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace sombra::bench {

struct BackendTiming {
    AccelKind kind = AccelKind::Bvh;
    double build_seconds = 0;   // median over the rounds
    double render_seconds = 0;  // median over the rounds
    std::uint64_t rays = 0;     // camera + shadow rays of one render
    std::size_t accel_bytes = 0;
    // The process's peak resident memory while this backend built and
    // rendered in the check (the scene's mesh included; 0 where the kernel
    // cannot reset the peak, see reset_peak_rss).
    std::uint64_t peak_rss_bytes = 0;
    double mrays_per_second() const { return render_seconds > 0 ? double(rays) / render_seconds * 1e-6 : 0; }
};

struct SceneMeasurement {
    std::uint64_t triangles = 0;
    std::vector<BackendTiming> backends;  // in compared_accels() order
    // The first backend's image against each other one's (the worst); all
    // pixels equal when there is only one backend.
    ImageAgreement agreement;
    // The BVH against the brute-force loop on a sample of pixel centres (the
    // check that still compares two implementations when Embree is absent).
    ImageAgreement brute_agreement;
};

// Measures `scene` rendered with `settings`, all hardware threads. Throws
// Error(name, ...) when the backends' images agree in fewer than
// kMinEqualFraction of the pixels, or the BVH and the brute-force loop
// disagree on a sampled pixel centre: no numbers for a wrong result.
SceneMeasurement measure_scene(const Scene& scene, const RenderSettings& settings, int reps, const std::string& name,
                               const EmbreeSettings& embree = {});

}  // namespace sombra::bench
