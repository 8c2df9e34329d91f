// Watertightness: a ray never slips between two triangles that share an edge
// or a corner. Möller–Trumbore computes a shared edge's barycentric with a
// different formula in each neighbour (relative to each one's first corner),
// so rounding can leave both slightly negative; triangle.h settles such
// near-edge cases with a test that both neighbours evaluate identically.
// These tests aim rays where that matters: from inside closed meshes (every
// ray must hit), exactly at the vertices and edge midpoints of a tilted quad
// grid, and through the pixel of manylights.json where the teapot leaked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "io/mesh_file.h"
#include "io/scene_json/scene_file.h"
#include "render/camera.h"

namespace sombra {
namespace {

const std::filesystem::path kShared = SOMBRA_SHARED_DIR;

// Rays that hit nothing, and hits that break the integrator's contract
// (t outside (0, tmax), barycentrics outside the triangle or non-finite).
struct Escapes {
    int rays = 0;
    int misses = 0;
    int bad_hits = 0;
    std::string first_escape;  // the first missing ray, in hex floats to replay it
};

Escapes trace_all(const Accel& accel, const std::vector<Ray>& rays, std::size_t stride = 1) {
    Escapes e;
    for (std::size_t i = 0; i < rays.size(); i += stride) {
        Hit hit;
        ++e.rays;
        if (!intersect(accel, rays[i], hit)) {
            ++e.misses;
            if (e.first_escape.empty()) {
                char text[160];
                std::snprintf(text, sizeof text, "first escape: o=(%a, %a, %a) d=(%a, %a, %a)", rays[i].origin.x,
                              rays[i].origin.y, rays[i].origin.z, rays[i].dir.x, rays[i].dir.y, rays[i].dir.z);
                e.first_escape = text;
            }
            continue;
        }
        const bool good = std::isfinite(hit.t) && hit.t > 0 && hit.t < rays[i].tmax && hit.b1 >= 0 && hit.b2 >= 0 &&
                          hit.b1 + hit.b2 <= 1;
        e.bad_hits += !good;
    }
    return e;
}

void report(const char* what, const Escapes& e) {
    std::printf("[ watertight ] %-34s %7d rays, %d escaped, %d bad hits\n", what, e.rays, e.misses, e.bad_hits);
}

// Counts every crossing of the ray with the mesh (not just the closest).
int crossings(const TriangleMesh& mesh, const Ray& ray) {
    int n = 0;
    for (const Index3& tri : mesh.triangles) {
        float t, b1, b2;
        n += intersect_triangle(ray.origin, ray.dir, mesh.positions[tri[0]], mesh.positions[tri[1]],
                                mesh.positions[tri[2]], ray.tmax, t, b1, b2);
    }
    return n;
}

Vec3 random_direction(std::mt19937& rng) {
    std::normal_distribution<float> gauss;
    for (;;) {
        const Vec3 g{gauss(rng), gauss(rng), gauss(rng)};
        if (dot(g, g) > 1e-4f) return g;
    }
}

// `count` points inside a closed mesh: random points of the bounding box's
// middle half whose crossing counts along 7 random rays are all odd.
std::vector<Vec3> interior_points(const TriangleMesh& mesh, int count, std::uint32_t seed) {
    Vec3 lo{INFINITY}, hi{-INFINITY};
    for (const Vec3& p : mesh.positions) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.25f, 0.75f);
    std::vector<Vec3> points;
    for (int attempt = 0; attempt < 1000 && static_cast<int>(points.size()) < count; ++attempt) {
        const Vec3 p{lo.x + unit(rng) * (hi.x - lo.x), lo.y + unit(rng) * (hi.y - lo.y),
                     lo.z + unit(rng) * (hi.z - lo.z)};
        bool inside = true;
        for (int k = 0; k < 7 && inside; ++k) inside = crossings(mesh, Ray{p, random_direction(rng)}) % 2 == 1;
        if (inside) points.push_back(p);
    }
    return points;
}

// From inside a closed mesh every ray must hit. Random directions, plus rays
// aimed exactly at every vertex and every edge midpoint, where leaks happen.
void expect_closed_mesh_holds_water(const std::string& file) {
    const std::filesystem::path path = kShared / "models" / file;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing";
    Diagnostics diag;
    const TriangleMesh mesh = load_obj(path, diag).mesh;
    const std::vector<Vec3> points = interior_points(mesh, 4, 5);
    ASSERT_EQ(points.size(), 4u) << "could not find points inside " << file;

    std::mt19937 rng(17);
    std::vector<Ray> random_rays, aimed_rays;
    for (const Vec3& o : points) {
        for (int i = 0; i < 50000; ++i) random_rays.push_back(Ray{o, random_direction(rng)});
        for (const Vec3& v : mesh.positions) aimed_rays.push_back(Ray{o, v - o});
        for (const Index3& tri : mesh.triangles) {
            for (int k = 0; k < 3; ++k) {
                const Vec3 mid = 0.5f * (mesh.positions[tri[k]] + mesh.positions[tri[(k + 1) % 3]]);
                aimed_rays.push_back(Ray{o, mid - o});
            }
        }
    }
    const Accel bvh = make_accel(mesh, AccelKind::Bvh);
    const Accel brute = make_accel(mesh, AccelKind::Brute);
    const struct {
        const char* name;
        Escapes e;
    } runs[] = {
        {"bvh, random directions", trace_all(bvh, random_rays)},
        {"bvh, aimed at vertices/edges", trace_all(bvh, aimed_rays)},
        // The brute-force loop on every 10th ray: it is slow, and bit-identical to the BVH anyway.
        {"brute, random directions (1/10)", trace_all(brute, random_rays, 10)},
        {"brute, aimed (1/10)", trace_all(brute, aimed_rays, 10)},
    };
    for (const auto& run : runs) {
        report((file + ": " + run.name).c_str(), run.e);
        EXPECT_EQ(run.e.misses, 0) << file << ": " << run.name << "; " << run.e.first_escape;
        EXPECT_EQ(run.e.bad_hits, 0) << file << ": " << run.name;
    }
}

TEST(Watertight, RaysFromInsideSpotAlwaysHit) { expect_closed_mesh_holds_water("spot.obj"); }
TEST(Watertight, RaysFromInsideCowAlwaysHit) { expect_closed_mesh_holds_water("cow.obj"); }

// A 64×64 grid of quads on a tilted plane (so no coordinate is round), each
// split on a diagonal, alternating between the two diagonals. Rays from near
// and far, steep and oblique, aimed exactly at every interior vertex and at
// the midpoint of every interior edge and diagonal.
TEST(Watertight, RaysAimedAtSharedEdgesOfAQuadGridNeverPassThrough) {
    constexpr int kN = 64;
    const Vec3 corner{0.3173f, -0.211f, 0.0917f};
    const Vec3 a{0.01931f, 0.00537f, -0.00713f};  // one quad along i
    const Vec3 b{-0.00412f, 0.01787f, 0.00869f};  // one quad along j
    TriangleMesh mesh;
    auto vertex = [&](int i, int j) { return static_cast<std::uint32_t>(j * (kN + 1) + i); };
    for (int j = 0; j <= kN; ++j) {
        for (int i = 0; i <= kN; ++i)
            mesh.positions.push_back(corner + static_cast<float>(i) * a + static_cast<float>(j) * b);
    }
    for (int j = 0; j < kN; ++j) {
        for (int i = 0; i < kN; ++i) {
            const std::uint32_t v00 = vertex(i, j), v10 = vertex(i + 1, j), v01 = vertex(i, j + 1),
                                v11 = vertex(i + 1, j + 1);
            if ((i + j) % 2 == 0) {
                mesh.triangles.push_back({v00, v10, v11});
                mesh.triangles.push_back({v00, v11, v01});
            } else {
                mesh.triangles.push_back({v10, v11, v01});
                mesh.triangles.push_back({v10, v01, v00});
            }
        }
    }
    // Targets away from the grid's border, so each is surrounded by triangles.
    std::vector<Vec3> targets;
    auto p = [&](int i, int j) { return mesh.positions[vertex(i, j)]; };
    for (int j = 1; j < kN; ++j) {
        for (int i = 1; i < kN; ++i) {
            targets.push_back(p(i, j));
            targets.push_back(0.5f * (p(i, j) + p(i + 1, j)));
            targets.push_back(0.5f * (p(i, j) + p(i, j + 1)));
            targets.push_back((i + j) % 2 == 0 ? 0.5f * (p(i, j) + p(i + 1, j + 1))
                                               : 0.5f * (p(i + 1, j) + p(i, j + 1)));
        }
    }
    const Vec3 centre = corner + 32.0f * (a + b);
    const Vec3 normal = normalize(cross(a, b));
    const Vec3 side = normalize(a);
    const float size = length(a) * kN;
    std::vector<Ray> rays;
    for (const float height : {0.02f, 0.3f, 3.0f, 30.0f, 300.0f}) {
        for (const float slant : {0.0f, 0.7f}) {
            for (const float face : {1.0f, -1.0f}) {
                const Vec3 o = centre + (face * height * size) * normal + (slant * height * size) * side;
                for (const Vec3& t : targets) rays.push_back(Ray{o, t - o});
            }
        }
    }
    const Accel bvh = make_accel(mesh, AccelKind::Bvh);
    const Escapes e = trace_all(bvh, rays);
    report("quad grid: bvh", e);
    EXPECT_EQ(e.misses, 0) << e.first_escape;
    EXPECT_EQ(e.bad_hits, 0);
    const Escapes eb = trace_all(make_accel(mesh, AccelKind::Brute), rays, 16);
    report("quad grid: brute (1/16)", eb);
    EXPECT_EQ(eb.misses, 0) << eb.first_escape;
    EXPECT_EQ(eb.bad_hits, 0);
}

// The near-edge fallback must keep each edge's side: from far away (so the
// float test leaves points 1e-4 from an edge to the double-precision one),
// from either face and with either winding, points just inside every edge
// hit with weights in range and points just outside miss.
TEST(Watertight, NearEdgeDecisionsKeepTheirSide) {
    const Vec3 p0{0.1f, 0.2f, 0.3f}, p1{1.3f, 0.1f, 0.5f}, p2{0.4f, 1.1f, 0.2f};
    const Vec3 normal = normalize(cross(p1 - p0, p2 - p0));
    const Vec3 corners[3] = {p0, p1, p2};
    int checked = 0;
    for (int k = 0; k < 3; ++k) {
        const Vec3 a = corners[k], b = corners[(k + 1) % 3], opposite = corners[(k + 2) % 3];
        const Vec3 mid = 0.5f * (a + b);
        // In-plane unit vector from the edge's midpoint away from the triangle.
        Vec3 out = cross(b - a, normal);
        if (dot(out, opposite - mid) > 0) out = -out;
        out = normalize(out);
        for (const float offset : {1e-4f, 1e-3f}) {
            for (const float side : {-1.0f, 1.0f}) {  // −1: inside, +1: outside
                const Vec3 target = mid + (side * offset) * out;
                for (const float face : {1.0f, -1.0f}) {
                    const Vec3 o = target + (face * 300.0f) * normal + Vec3{0.7f, -0.4f, 0.2f};
                    for (const bool flipped : {false, true}) {
                        float t = -1, b1 = -1, b2 = -1;
                        const bool hit = flipped ? intersect_triangle(o, target - o, p0, p2, p1, INFINITY, t, b1, b2)
                                                 : intersect_triangle(o, target - o, p0, p1, p2, INFINITY, t, b1, b2);
                        EXPECT_EQ(hit, side < 0)
                            << "edge " << k << " offset " << offset << " face " << face << (flipped ? " flipped" : "");
                        if (hit) {
                            EXPECT_TRUE(b1 >= 0 && b2 >= 0 && b1 + b2 <= 1 && t > 0);
                        }
                        ++checked;
                    }
                }
            }
        }
    }
    EXPECT_EQ(checked, 3 * 2 * 2 * 2 * 2);
}

// shared/scenes/manylights.json, pixel (711, 420): the camera ray slipped
// through the diagonal shared by teapot triangles 1526 and 1527 and hit the
// inside of the far wall (triangle 1748), a black pixel.
TEST(Watertight, ManylightsPixelHitsTheTeapotsNearSide) {
    const std::filesystem::path path = kShared / "scenes" / "manylights.json";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing";
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(path, diag);
    const Scene& scene = loaded.scene;
    const RenderSettings& settings = loaded.settings;
    const Camera camera = make_camera(scene.camera, settings.width, settings.height);
    const Ray ray = camera_ray(camera, image_plane_s(711.5f, settings.width), image_plane_t(420.5f, settings.height));
    for (const AccelKind kind : {AccelKind::Bvh, AccelKind::Brute}) {
        const Accel accel = make_accel(scene, kind);
        Hit hit;
        ASSERT_TRUE(intersect(accel, ray, hit)) << accel_name(kind);
        EXPECT_TRUE(hit.triangle == 1526 || hit.triangle == 1527)
            << accel_name(kind) << " hit triangle " << hit.triangle << " at t=" << hit.t;
    }
}

}  // namespace
}  // namespace sombra
