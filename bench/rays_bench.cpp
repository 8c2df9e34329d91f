#include "rays_bench.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>

#include "core/error.h"
#include "io/scene_json/scene_file.h"

namespace sombra::bench {

namespace {

struct RayBatches {
    std::vector<Ray> closest, shadow;
};

// Rays leave a point of the surface, nudged off it along the normal by a
// small fraction of the scene's size so that they do not hit their own
// triangle at t ≈ 0 (the integrators offset their rays likewise).
RayBatches make_batches(const Scene& scene, int count) {
    const TriangleMesh& mesh = scene.geometry;
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    std::vector<std::uint32_t> usable;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
        const PreparedTriangle tri = prepare_triangle(mesh, mesh.triangles[t]);
        if (!is_hittable(tri)) continue;
        usable.push_back(t);
        for (Vec3 p : {tri.p0, tri.p1, tri.p2}) lo = min(lo, p), hi = max(hi, p);
    }
    RayBatches batches;
    if (usable.empty()) return batches;
    const float offset = 1e-5f * max_component(hi - lo);
    std::mt19937 rng(20261126);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_int_distribution<std::size_t> pick(0, usable.size() - 1);
    batches.closest.reserve(count);
    batches.shadow.reserve(count);
    for (int i = 0; i < count; ++i) {
        const PreparedTriangle tri = prepare_triangle(mesh, mesh.triangles[usable[pick(rng)]]);
        float u = unit(rng), v = unit(rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        const Vec3 n = normalize(tri.n);
        const Vec3 origin = tri.p0 + u * (tri.p1 - tri.p0) + v * (tri.p2 - tri.p0) + offset * n;
        Vec3 d;
        do {
            d = Vec3{2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1};
        } while (dot(d, d) > 1.0f || dot(d, d) < 1e-6f);
        d = normalize(d);
        batches.closest.push_back(Ray{origin, dot(d, n) < 0 ? -d : d});
        const Vec3 target = scene.lights.empty()
                                ? lo + Vec3{unit(rng), unit(rng), unit(rng)} * (hi - lo)
                                : scene.lights[static_cast<std::size_t>(i) % scene.lights.size()].position;
        batches.shadow.push_back(Ray{origin, target - origin, 1.0f});
    }
    return batches;
}

// The BVH against brute force on every stride-th ray of both batches.
void check_against_brute(const Accel& bvh, const Accel& brute, const RayBatches& batches, const std::string& name) {
    const std::size_t stride = std::max<std::size_t>(1, batches.closest.size() / 500);
    for (std::size_t i = 0; i < batches.closest.size(); i += stride) {
        Hit a, b;
        const bool ha = intersect(bvh, batches.closest[i], a), hb = intersect(brute, batches.closest[i], b);
        const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
        const bool same_hit = bits(a.t) == bits(b.t) && bits(a.b1) == bits(b.b1) && bits(a.b2) == bits(b.b2) &&
                              a.triangle == b.triangle && a.has_corners &&
                              a.corners == triangle_corners(*bvh.mesh, a.triangle);
        if (ha != hb || (ha && !same_hit))
            throw Error(name, "the BVH's closest hit differs from brute force on ray " + std::to_string(i));
        if (occluded(bvh, batches.shadow[i]) != occluded(brute, batches.shadow[i]))
            throw Error(name, "the BVH's occlusion differs from brute force on shadow ray " + std::to_string(i));
    }
}

// Seconds to trace one batch; `hits` counts the rays that hit (occluded
// ones for shadow rays), which also keeps the answers in use.
double trace_batch(const Accel& accel, const std::vector<Ray>& rays, bool shadow, std::size_t& hits) {
    const Clock::time_point start = Clock::now();
    hits = 0;
    for (const Ray& ray : rays) {
        Hit hit;
        hits += shadow ? occluded(accel, ray) : intersect(accel, ray, hit);
    }
    return seconds_since(start);
}

}  // namespace

void run_rays_bench(const std::vector<std::string>& scene_files, const RaysBenchOptions& o, std::ostream& out) {
    Table table;
    table.header = {"scene", "triangles", "rays", "kind", "hit", "accel", "seconds", "Mrays/s", "bvh ÷ embree"};
    table.right = {false, true, true, false, true, false, true, true, true};
    for (const std::string& file : scene_files) {
        const std::string name = std::filesystem::path(file).stem().string();
        std::cerr << "sombra-bench: " << name << ": loading\n";
        Diagnostics diag;
        const Scene scene = load_scene_file(file, diag).scene;
        const RayBatches batches = make_batches(scene, o.rays);
        if (batches.closest.empty()) throw Error(file, "no triangle can be hit: nothing to trace");
        std::vector<Accel> accels;
        for (AccelKind kind : compared_accels()) accels.push_back(make_compared_accel(scene, kind, o.embree));
        std::cerr << "sombra-bench: " << name << ": checking the BVH against brute force\n";
        check_against_brute(accels[0], make_accel(scene, AccelKind::Brute), batches, file);
        std::cerr << "sombra-bench: " << name << ": " << o.reps << " rounds of " << o.rays << " rays of each kind\n";
        for (const bool shadow : {false, true}) {
            const std::vector<Ray>& rays = shadow ? batches.shadow : batches.closest;
            std::vector<std::vector<double>> times(accels.size());
            std::vector<std::size_t> hits(accels.size(), 0);
            for (int round = 0; round < o.reps; ++round) {
                for (std::size_t k = 0; k < accels.size(); ++k) {
                    const std::size_t a = (k + static_cast<std::size_t>(round)) % accels.size();
                    times[a].push_back(trace_batch(accels[a], rays, shadow, hits[a]));
                }
            }
            // Each backend's own share of rays that hit: a yardstick that
            // answers differently (Embree's robust mode near t = 0) shows here.
            const auto hit_share = [&](std::size_t a) {
                return fixed(100.0 * double(hits[a]) / double(rays.size()), 1) + " %";
            };
            std::vector<double> medians;
            for (const auto& t : times) medians.push_back(median(t));
            for (std::size_t a = 0; a < accels.size(); ++a) {
                const bool first = a == 0;
                table.rows.push_back(
                    {first && !shadow ? name : "", first && !shadow ? thousands(scene.geometry.triangles.size()) : "",
                     first ? thousands(rays.size()) : "", first ? (shadow ? "shadow" : "closest hit") : "",
                     hit_share(a), accel_label(accels[a].kind, o.embree), seconds(medians[a]),
                     fixed(double(rays.size()) / medians[a] / 1e6, 2), a == 1 ? ratio(medians[0], medians[1]) : ""});
            }
        }
    }
    out << to_markdown(table);
}

}  // namespace sombra::bench
