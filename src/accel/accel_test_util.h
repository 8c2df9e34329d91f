// Test helpers shared by the BVH tests: random geometry and a ray-by-ray
// comparison of the BVH against the brute-force reference.
#pragma once

#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "accel/accel.h"

namespace sombra::testing {

inline Vec3 random_point(std::mt19937& rng, Vec3 lo, Vec3 hi) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    return {lo.x + unit(rng) * (hi.x - lo.x), lo.y + unit(rng) * (hi.y - lo.y), lo.z + unit(rng) * (hi.z - lo.z)};
}

// Appends triangle (a, b, c) to `mesh` with its own three vertices.
inline void add_triangle(TriangleMesh& mesh, Vec3 a, Vec3 b, Vec3 c) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.triangles.push_back({base, base + 1, base + 2});
}

// `count` triangles with corners within `size` of random centres in [0, 1]³.
inline TriangleMesh random_soup(int count, std::uint32_t seed, float size = 0.15f) {
    std::mt19937 rng(seed);
    TriangleMesh mesh;
    for (int i = 0; i < count; ++i) {
        const Vec3 c = random_point(rng, Vec3{0.0f}, Vec3{1.0f});
        add_triangle(mesh, random_point(rng, c - Vec3{size}, c + Vec3{size}),
                     random_point(rng, c - Vec3{size}, c + Vec3{size}),
                     random_point(rng, c - Vec3{size}, c + Vec3{size}));
    }
    return mesh;
}

// The triangles the BVH's leaves hold, in leaf order (empty lanes left out).
inline std::vector<std::uint32_t> bvh_triangles(const Bvh& bvh) {
    std::vector<std::uint32_t> out;
    for (const TriangleBlock& block : bvh.blocks) {
        for (std::uint32_t t : block.triangle) {
            if (t != kBvhEmptyLane) out.push_back(t);
        }
    }
    return out;
}

// A point on a random triangle of `mesh` (its corners' random blend); at
// least one triangle must have all its indices in range.
inline Vec3 random_surface_point(const TriangleMesh& mesh, std::mt19937& rng) {
    std::uniform_int_distribution<std::size_t> pick(0, mesh.triangles.size() - 1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Index3 tri = mesh.triangles[pick(rng)];
    while (tri[0] >= mesh.positions.size() || tri[1] >= mesh.positions.size() || tri[2] >= mesh.positions.size()) {
        tri = mesh.triangles[pick(rng)];  // meshes made to test bad indices have good ones too
    }
    float b1 = unit(rng), b2 = unit(rng);
    if (b1 + b2 > 1) {
        b1 = 1 - b1;
        b2 = 1 - b2;
    }
    return (1 - b1 - b2) * mesh.positions[tri[0]] + b1 * mesh.positions[tri[1]] + b2 * mesh.positions[tri[2]];
}

// Rays from random origins in [lo, hi] towards targets: half at points of
// the surface, half anywhere in the box. About one ray in four has one or
// two direction components set to +0 or −0, one in three a finite tmax.
inline std::vector<Ray> random_rays(const TriangleMesh& mesh, int count, std::uint32_t seed, Vec3 lo, Vec3 hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        Ray ray;
        ray.origin = random_point(rng, lo, hi);
        const Vec3 target =
            (i % 2 == 0 && !mesh.triangles.empty()) ? random_surface_point(mesh, rng) : random_point(rng, lo, hi);
        ray.dir = (target - ray.origin) * (0.25f + 2 * unit(rng));
        if (i % 4 == 1) {
            const int axis = i % 3;
            ray.dir[axis] = (i % 8 == 1) ? 0.0f : -0.0f;
            if (i % 12 == 1) ray.dir[(axis + 1) % 3] = 0.0f;
        }
        if (ray.dir == Vec3{}) ray.dir = Vec3{0, 0, 1};
        if (i % 3 == 2) ray.tmax = 1.2f * unit(rng);
        rays.push_back(ray);
    }
    return rays;
}

// Traces every ray with both backends; counts hits and any difference in
// (hit?, triangle, t, b1, b2) or in occluded(), describing the first.
struct Comparison {
    int hits = 0;
    int occluded = 0;
    int mismatches = 0;
    std::string first_mismatch;
};

inline std::string describe(const Ray& ray) {
    std::ostringstream out;
    out.precision(9);
    out << "ray o=(" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") d=(" << ray.dir.x << ", "
        << ray.dir.y << ", " << ray.dir.z << ") tmax=" << ray.tmax;
    return out.str();
}

inline std::string describe(bool found, const Hit& hit) {
    if (!found) return "miss";
    std::ostringstream out;
    out.precision(9);
    out << "triangle " << hit.triangle << " t=" << hit.t << " b=(" << hit.b1 << ", " << hit.b2 << ")";
    return out.str();
}

// Brute force against the BVH on every ray: the same hits (triangle, t,
// weights; the BVH's corners against the mesh's), and occlusion.
inline Comparison compare_with_brute(const TriangleMesh& mesh, const std::vector<Ray>& rays) {
    const Accel brute = make_accel(mesh, AccelKind::Brute);
    const Accel bvh = make_accel(mesh, AccelKind::Bvh);
    Comparison result;
    for (const Ray& ray : rays) {
        Hit want, got;
        const bool want_found = intersect(brute, ray, want);
        const bool got_found = intersect(bvh, ray, got);
        const bool want_occluded = occluded(brute, ray);
        const bool got_occluded = occluded(bvh, ray);
        result.hits += want_found;
        result.occluded += want_occluded;
        // occluded() must agree with intersect() in each backend, and the backends with each other.
        const bool same = want_found == got_found && want_occluded == got_occluded && got_occluded == got_found &&
                          (!want_found || (want.triangle == got.triangle && want.t == got.t && want.b1 == got.b1 &&
                                           want.b2 == got.b2 && got.has_corners &&
                                           got.corners == triangle_corners(mesh, got.triangle)));
        if (same) continue;
        if (result.mismatches++ == 0) {
            result.first_mismatch = describe(ray) + ": brute " + describe(want_found, want) +
                                    (want_occluded ? " (occluded)" : "") + ", bvh " + describe(got_found, got) +
                                    (got_occluded ? " (occluded)" : "");
        }
    }
    return result;
}

}  // namespace sombra::testing
