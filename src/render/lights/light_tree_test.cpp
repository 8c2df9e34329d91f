// The light tree: its choice probabilities form a distribution (the rest
// being the chance the descent fails), sampling follows them (χ²), the pmf
// MIS evaluates is bit for bit the sampled probability, the importance never
// rules out an emitter that can light the point, and under many lights the
// path integrator estimates the same radiance as with power-proportional
// choice, with less variance.
#include "render/lights/light_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "accel/accel.h"
#include "render/chi2_test_util.h"
#include "render/integrator.h"
#include "render/lights/lights.h"
#include "render/sampler.h"
#include "render/test_meshes.h"

namespace sombra {
namespace {

using testing::add_triangle;

float uniform(std::uint32_t& counter, std::uint64_t key) { return hash_to_unit(counter++, key); }

Vec3 random_in_cube(std::uint32_t& c, std::uint64_t key, float half) {
    const float x = uniform(c, key), y = uniform(c, key), z = uniform(c, key);
    return Vec3{(2 * x - 1) * half, (2 * y - 1) * half, (2 * z - 1) * half};
}

Vec3 random_direction(std::uint32_t& c, std::uint64_t key) {
    for (;;) {
        const Vec3 v = random_in_cube(c, key, 1.0f);
        const float l2 = dot(v, v);
        if (l2 > 1e-4f && l2 <= 1.0f) return v / std::sqrt(l2);
    }
}

// `count` small random triangles in a cube of half-size `spread`, one in
// three shining from both faces, powers over three decades.
std::vector<LightTreeEmitter> random_emitters(int count, float spread, std::uint64_t key) {
    std::vector<LightTreeEmitter> emitters;
    std::uint32_t c = 0;
    for (int i = 0; i < count; ++i) {
        const Vec3 p = random_in_cube(c, key, spread);
        const Vec3 a = random_direction(c, key), b = random_direction(c, key);
        const float size = 0.05f + 0.5f * uniform(c, key);
        LightTreeEmitter e{p, p + size * a, p + size * b, std::pow(10.0f, 3 * uniform(c, key)), i % 3 == 0};
        if (length(cross(e.p1 - e.p0, e.p2 - e.p0)) < 1e-3f) continue;
        emitters.push_back(e);
    }
    return emitters;
}

struct Shading {
    Vec3 x, n;
};

std::vector<Shading> shading_points(std::uint64_t key) {
    std::vector<Shading> points;
    std::uint32_t c = 0;
    for (int i = 0; i < 6; ++i)
        points.push_back({random_in_cube(c, key, 8.0f), i == 5 ? Vec3{0.0f} : random_direction(c, key)});
    return points;
}

TEST(LightTree, NodesAre48BytesAndEveryEmitterHasOneLeaf) {
    static_assert(sizeof(LightTreeNode) == 48);
    const std::vector<LightTreeEmitter> emitters = random_emitters(300, 5.0f, 1);
    const LightTree tree = make_light_tree(emitters);
    ASSERT_EQ(tree.nodes.size(), 2 * emitters.size() - 1);
    std::vector<int> seen(emitters.size(), 0);
    for (const LightTreeNode& node : tree.nodes)
        if (node.leaf()) ++seen[node.index()];
    for (int s : seen) EXPECT_EQ(s, 1);
    // One emitter: a lone leaf, chosen with probability 1 wherever it can shine.
    const LightTree one = make_light_tree({emitters[1]});
    ASSERT_EQ(one.nodes.size(), 1u);
    EXPECT_TRUE(make_light_tree({}).nodes.empty());
}

TEST(LightTree, PmfIsADistributionAndSamplingFollowsIt) {
    const std::vector<LightTreeEmitter> emitters = random_emitters(64, 4.0f, 2);
    const LightTree tree = make_light_tree(emitters);
    for (const Shading& s : shading_points(3)) {
        std::vector<double> pmf(emitters.size() + 1);  // last: the descent fails
        double sum = 0;
        for (std::uint32_t e = 0; e < emitters.size(); ++e) sum += pmf[e] = pmf_light_tree(tree, s.x, s.n, e);
        EXPECT_LE(sum, 1.0 + 1e-5);
        pmf.back() = std::max(0.0, 1.0 - sum);
        const int n = 200000;
        std::vector<double> counts(pmf.size(), 0.0);
        for (int k = 0; k < n; ++k) {
            const LightTreeChoice choice =
                sample_light_tree(tree, s.x, s.n, hash_to_unit(static_cast<std::uint32_t>(k), 7));
            if (!(choice.probability > 0.0f)) {
                counts.back() += 1;
                continue;
            }
            ASSERT_LT(choice.emitter, emitters.size());
            counts[choice.emitter] += 1;
            // MIS needs the very same float, not a close one.
            ASSERT_EQ(choice.probability, pmf_light_tree(tree, s.x, s.n, choice.emitter));
        }
        // Pearson's χ², pooling categories expected to hold fewer than 5; a
        // category of pmf 0 must never be sampled.
        std::vector<double> expected(pmf.size());
        for (std::size_t i = 0; i < pmf.size(); ++i) expected[i] = pmf[i] * n;
        const chi2::Pearson test = chi2::pearson(counts, expected);
        EXPECT_EQ(test.bad_bin, -1) << "category of pmf 0 sampled";
        ASSERT_GT(test.dof, 0);
        EXPECT_GT(test.p_value, 1e-4) << "χ² " << test.chi2 << " with " << test.dof << " dof";
    }
}

// Whether a triangle emitter can send light to x (any point of its front,
// or either face when two-sided, faces x), regardless of x's normal: the
// path integrator weighs by |cos| at x, 0 only in x's tangent plane.
bool can_light(const LightTreeEmitter& e, Vec3 x, Vec3 n) {
    const Vec3 nw = cross(e.p1 - e.p0, e.p2 - e.p0);
    const float side = dot(nw, x - e.p0);
    if (e.two_sided ? side == 0.0f : !(side > 0.0f)) return false;
    if (n == Vec3{0.0f}) return true;
    // Some corner off x's tangent plane.
    return dot(n, e.p0 - x) != 0.0f || dot(n, e.p1 - x) != 0.0f || dot(n, e.p2 - x) != 0.0f;
}

TEST(LightTree, ImportanceIsConservative) {
    for (std::uint64_t seed = 10; seed < 40; ++seed) {
        const std::vector<LightTreeEmitter> emitters = random_emitters(50, 3.0f, seed);
        const LightTree tree = make_light_tree(emitters);
        for (const Shading& s : shading_points(seed * 7)) {
            int dark = 0;
            for (std::uint32_t e = 0; e < emitters.size(); ++e) {
                const float p = pmf_light_tree(tree, s.x, s.n, e);
                if (can_light(emitters[e], s.x, s.n))
                    EXPECT_GT(p, 0.0f) << "seed " << seed << " emitter " << e;
                else
                    dark += p == 0.0f;
            }
            (void)dark;
        }
    }
}

TEST(LightTree, OneSidedEmittersFacingAwayGetNothing) {
    // A row of eight one-sided triangles shining down (−y); seen from far
    // above, none can light the point and each has probability 0; from
    // below, all do and none has.
    std::vector<LightTreeEmitter> emitters;
    for (int i = 0; i < 8; ++i) {
        const Vec3 p{static_cast<float>(i), 0, 0};
        emitters.push_back({p, p + Vec3{0.5f, 0, 0}, p + Vec3{0, 0, 0.5f}, 1.0f + static_cast<float>(i), false});
    }
    ASSERT_LT(cross(emitters[0].p1 - emitters[0].p0, emitters[0].p2 - emitters[0].p0).y, 0.0f);
    const LightTree tree = make_light_tree(emitters);
    for (std::uint32_t e = 0; e < 8; ++e) {
        EXPECT_EQ(pmf_light_tree(tree, {3.5f, 30, 0}, {0, -1, 0}, e), 0.0f);
        EXPECT_GT(pmf_light_tree(tree, {3.5f, -3, 0}, {0, 1, 0}, e), 0.0f);
    }
    EXPECT_EQ(sample_light_tree(tree, {3.5f, 30, 0}, {0, -1, 0}, 0.3f).probability, 0.0f);
    // Half of them turned to shine up: from above only those are chosen.
    for (int i = 0; i < 8; i += 2)
        std::swap(emitters[static_cast<std::size_t>(i)].p1, emitters[static_cast<std::size_t>(i)].p2);
    const LightTree mixed = make_light_tree(emitters);
    double sum = 0;
    for (std::uint32_t e = 0; e < 8; ++e) {
        const float p = pmf_light_tree(mixed, {3.5f, 30, 0}, {0, -1, 0}, e);
        if (e % 2 == 0)
            EXPECT_GT(p, 0.0f);
        else
            EXPECT_EQ(p, 0.0f);
        sum += p;
    }
    EXPECT_NEAR(sum, 1.0, 1e-5);
}

// A diffuse floor under a 40 × 25 grid of small emissive quads (2000
// triangles) at heights 0.3–3, tilted at random, a third one-sided, in
// three colours over two decades of brightness.
Scene many_lights_scene() {
    std::vector<Material> materials;
    Material floor;
    floor.kd = Vec3{0.5f};
    materials.push_back(floor);
    for (int m = 0; m < 6; ++m) {
        Material light;
        light.kd = Vec3{0.0f};
        const float scale = std::pow(10.0f, static_cast<float>(m % 3) - 1.0f);
        light.ke = scale * (m < 3 ? Vec3{20, 12, 6} : Vec3{6, 12, 20});
        light.emits_front_only = m % 2 == 1;
        materials.push_back(light);
    }
    TriangleMesh mesh;
    add_triangle(mesh, {-30, 0, -30}, {-30, 0, 30}, {30, 0, 30}, 0);
    add_triangle(mesh, {-30, 0, -30}, {30, 0, 30}, {30, 0, -30}, 0);
    std::uint32_t c = 0;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 25; ++j) {
            const Vec3 centre{-20 + static_cast<float>(i), 0.3f + 2.7f * uniform(c, 5), -12 + static_cast<float>(j)};
            // Facing mostly down, tilted up to ~70°.
            Vec3 nrm = random_direction(c, 6);
            nrm = normalize(Vec3{nrm.x, -1.2f - std::fabs(nrm.y), nrm.z});
            const Vec3 t = normalize(cross(nrm, Vec3{1, 0, 0}));
            const Vec3 b = cross(nrm, t);
            const float h = 0.1f + 0.1f * uniform(c, 7);
            const auto material = 1 + static_cast<std::uint32_t>(uniform(c, 8) * 6);
            const Vec3 p0 = centre - h * t - h * b, p1 = centre + h * t - h * b, p2 = centre + h * t + h * b,
                       p3 = centre - h * t + h * b;
            // Wound so that the front faces along nrm.
            const bool along = dot(cross(p1 - p0, p2 - p0), nrm) > 0.0f;
            add_triangle(mesh, p0, along ? p1 : p2, along ? p2 : p1, material);
            add_triangle(mesh, p0, along ? p2 : p3, along ? p3 : p2, material);
        }
    SceneBuilder builder;
    testing::add_world_mesh(builder, mesh, materials);
    return builder.finish();
}

struct Estimate {
    double sum = 0, sum2 = 0;
    long n = 0;
    double mean() const { return sum / static_cast<double>(n); }
    double variance() const { return std::max(0.0, sum2 / static_cast<double>(n) - mean() * mean()); }
    double standard_error() const { return std::sqrt(variance() / static_cast<double>(n - 1)); }
};

Estimate estimate_floor(const Scene& scene, const Accel& accel, LightSelection selection, Vec3 x, int samples) {
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true, selection);
    EXPECT_EQ(lights.use_tree, selection == LightSelection::Tree);
    const IntegratorContext ctx{&scene, &accel, &lights, 2};
    RayCounters counters;
    Estimate e;
    for (int k = 0; k < samples; ++k) {
        SampleStream stream{mix64(0x51ed + static_cast<std::uint64_t>(k)), 0, 1};
        const double l = luminance(trace_path(ctx, Ray{x + Vec3{0, 0.05f, 0}, Vec3{0, -1, 0}}, stream, counters));
        e.sum += l;
        e.sum2 += l * l;
        ++e.n;
    }
    EXPECT_EQ(counters.nonfinite_samples, 0u);
    return e;
}

TEST(LightTree, PathIntegratorUnderManyLightsAgreesWithPowerChoiceAndIsLessNoisy) {
    const Scene scene = many_lights_scene();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    for (const Vec3 x : {Vec3{0.2f, 0, 0.3f}, Vec3{-15.5f, 0, 8.2f}, Vec3{25, 0, -20}}) {
        const Estimate power = estimate_floor(scene, accel, LightSelection::Power, x, 20000);
        const Estimate tree = estimate_floor(scene, accel, LightSelection::Tree, x, 20000);
        const double z = (tree.mean() - power.mean()) / std::hypot(tree.standard_error(), power.standard_error());
        EXPECT_LT(std::fabs(z), 5.0) << "tree " << tree.mean() << " vs power " << power.mean();
        const double ratio = tree.variance() / power.variance();
        std::printf("    at (%g, %g): L = %.4f, variance tree / power = %.3f\n", x.x, x.z, tree.mean(), ratio);
        // Only a clear regression fails: the measured ratios are far below 1.
        EXPECT_LT(ratio, 1.5);
    }
}

}  // namespace
}  // namespace sombra
