// Helpers of the path integrator's statistical tests
// (path_integrator_test.cpp, path_volume_test.cpp): estimates with their
// standard error from the sample variance, z-tests against closed forms,
// a sphere mesh and a runner of trace_path. For tests only.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "render/integrator.h"
#include "render/render.h"
#include "render/test_meshes.h"

namespace sombra::testing {

// |z| beyond this fails: about 1 in 10^6 for a correct estimator, so the
// whole file (a few dozen z-tests) passes by chance failure ~never.
inline constexpr double kZ = 5.0;

// Mean and standard error of a stream of per-sample estimates.
struct Estimate {
    double sum = 0, sum2 = 0;
    long n = 0;
    void add(double x) {
        sum += x;
        sum2 += x * x;
        ++n;
    }
    double mean() const { return sum / static_cast<double>(n); }
    double standard_error() const {
        const double m = mean();
        const double var =
            std::max(0.0, sum2 / static_cast<double>(n) - m * m) * static_cast<double>(n) / static_cast<double>(n - 1);
        return std::sqrt(var / static_cast<double>(n));
    }
};

// z of `e` against `expected`; a zero-variance estimate must equal it to float rounding.
inline void expect_agrees(const Estimate& e, double expected, const char* what) {
    const double se = e.standard_error();
    if (se < 1e-9) {
        EXPECT_NEAR(e.mean(), expected, 1e-5 * std::max(1.0, std::fabs(expected))) << what;
        return;
    }
    const double z = (e.mean() - expected) / se;
    EXPECT_LT(std::fabs(z), kZ) << what << ": mean " << e.mean() << " ± " << se << ", expected " << expected;
}

// A flat-shaded sphere (subdivided octahedron, corners pushed onto the
// sphere), wound counter-clockwise seen from outside.
inline void add_sphere(TriangleMesh& mesh, Vec3 centre, float radius, int levels, std::uint32_t material) {
    struct Tri {
        Vec3 a, b, c;
    };
    std::vector<Tri> tris;
    const Vec3 px{1, 0, 0}, nx{-1, 0, 0}, py{0, 1, 0}, ny{0, -1, 0}, pz{0, 0, 1}, nz{0, 0, -1};
    tris = {{px, py, pz}, {py, nx, pz}, {nx, ny, pz}, {ny, px, pz},
            {py, px, nz}, {nx, py, nz}, {ny, nx, nz}, {px, ny, nz}};
    for (int l = 0; l < levels; ++l) {
        std::vector<Tri> finer;
        for (const Tri& t : tris) {
            const Vec3 ab = normalize(t.a + t.b), bc = normalize(t.b + t.c), ca = normalize(t.c + t.a);
            finer.push_back({t.a, ab, ca});
            finer.push_back({ab, t.b, bc});
            finer.push_back({ca, bc, t.c});
            finer.push_back({ab, bc, ca});
        }
        tris = std::move(finer);
    }
    for (const Tri& t : tris)
        add_triangle(mesh, centre + radius * t.a, centre + radius * t.b, centre + radius * t.c, material);
}

// Samples of trace_path for rays from `origin` towards random points of
// the unit square around `target` (a small pixel footprint), red channel.
// With `pixel_samples` 1 every sample has a pixel key of its own (version
// 1's hashed draws); with more, the samples come `pixel_samples` to a key,
// as a pixel's progressive Owen-scrambled Sobol draws. Their standard error
// from the sample variance then over-estimates the true one (stratified
// samples within a pixel correlate negatively for these smooth
// integrands), so the z-test stays a test of bias.
struct PathRun {
    const Scene& scene;
    int max_depth = 8;
    LightStrategy strategy = LightStrategy::Mis;
    std::uint32_t pixel_samples = 1;
    int max_volume_depth = 256;

    Estimate estimate(Vec3 origin, Vec3 target, int samples, std::uint64_t seed, int channel = 0) const {
        const Accel accel = make_accel(scene, AccelKind::Bvh);
        const bool path = true;
        const LightSet lights = make_light_set(scene, make_constant_environment(scene.background), path);
        const IntegratorContext ctx{&scene, &accel, &lights, max_depth, strategy, max_volume_depth};
        Estimate e;
        RayCounters counters;
        for (int k = 0; k < samples; ++k) {
            const auto n = static_cast<std::uint32_t>(k);
            SampleStream stream{mix64(seed + n / pixel_samples), n % pixel_samples, pixel_samples};
            const Vec3 l = trace_path(ctx, Ray{origin, target - origin}, stream, counters);
            e.add(l[channel]);
        }
        EXPECT_EQ(counters.nonfinite_samples, 0u);
        return e;
    }
};

// A homogeneous medium (spec §26) named "medium".
inline Medium homogeneous(Vec3 sigma_a, Vec3 sigma_s, float g = 0.0f) {
    Medium m;
    m.name = "medium";
    m.sigma_a = sigma_a;
    m.sigma_s = sigma_s;
    m.g = g;
    return m;
}

// A black diffuse material emitting `radiance` (from both sides).
inline Material emitter(float radiance) {
    Material m;
    m.type = MaterialType::Diffuse;
    m.kd = Vec3{0.0f};
    m.ke = Vec3{radiance};
    return m;
}

}  // namespace sombra::testing
