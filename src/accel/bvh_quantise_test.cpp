// Quantised child boxes (bvh_quantise.cpp): each decoded box contains its
// child's box, within one grid step, for ordinary boxes and for the ones
// where float rounding bites (far from the origin, tiny, flat, huge); and
// the BVH still finds exactly brute force's hits on meshes made of those.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "accel/accel_test_util.h"
#include "accel/bvh.h"
#include "accel/bvh_quantise.h"

namespace sombra {
namespace {

using testing::add_triangle;
using testing::compare_with_brute;
using testing::Comparison;

// Two ulps of the larger magnitude: the rounding of a plane's sum.
float two_ulps(float a, float b) {
    const float m = std::max(std::abs(a), std::abs(b));
    return 2.0f * (std::nextafter(m, std::numeric_limits<float>::infinity()) - m);
}

// Quantises `boxes` and checks every plane: on the outer side of the true
// bound, and within a grid step of it. Returns the number of failures.
int check_quantised(const std::vector<BvhChildBox>& boxes) {
    BvhWideNode node{};
    quantise_children(boxes.data(), static_cast<int>(boxes.size()), node);
    int failures = 0;
    for (int i = 0; i < kBvhWidth; ++i) {
        const bool should_be_used = i < static_cast<int>(boxes.size());
        if (slot_used(node, i) != should_be_used) ++failures;
        if (!should_be_used) continue;
        const BvhChildBox decoded = child_box(node, i);
        for (int a = 0; a < 3; ++a) {
            const float step = node.scale[a];
            const float lo = boxes[i].lo[a], hi = boxes[i].hi[a];
            if (!(decoded.lo[a] <= lo) || !(decoded.hi[a] >= hi)) {
                ADD_FAILURE() << "child " << i << " axis " << a << ": [" << lo << ", " << hi << "] not inside ["
                              << decoded.lo[a] << ", " << decoded.hi[a] << "]";
                ++failures;
            }
            if (lo - decoded.lo[a] > step * 1.001f + two_ulps(lo, decoded.lo[a]) ||
                decoded.hi[a] - hi > step * 1.001f + two_ulps(hi, decoded.hi[a])) {
                ADD_FAILURE() << "child " << i << " axis " << a << ": decoded [" << decoded.lo[a] << ", "
                              << decoded.hi[a] << "] looser than one step " << step << " around [" << lo << ", "
                              << hi << "]";
                ++failures;
            }
        }
    }
    return failures;
}

// Random boxes inside a region of size `extent` centred at `centre`.
std::vector<BvhChildBox> random_boxes(std::mt19937& rng, int count, Vec3 centre, float extent) {
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    std::vector<BvhChildBox> boxes;
    for (int i = 0; i < count; ++i) {
        Vec3 a, b;
        for (int k = 0; k < 3; ++k) {
            a[k] = centre[k] + extent * u(rng);
            b[k] = centre[k] + extent * u(rng);
        }
        boxes.push_back({min(a, b), max(a, b)});
    }
    return boxes;
}

TEST(BvhQuantise, DecodedBoxesContainTheChildrenWithinOneStep) {
    std::mt19937 rng(31);
    const float centres[] = {0.0f, 1.0f, -3.5f, 1e3f, 1e6f, -3e7f};
    const float extents[] = {1.0f, 1e-3f, 1e-6f, 0.5f, 2e4f};
    for (float c : centres) {
        for (float e : extents) {
            for (int size = 1; size <= kBvhWidth; ++size) {
                ASSERT_EQ(check_quantised(random_boxes(rng, size, Vec3{c, -c, 0.5f * c}, e)), 0)
                    << "centre " << c << ", extent " << e << ", " << size << " children";
            }
        }
    }
}

TEST(BvhQuantise, FlatPointLikeAndHugeBoxes) {
    // A wall: zero extent along x; a point; children that share faces.
    EXPECT_EQ(check_quantised({{{1, 0, 0}, {1, 2, 2}}, {{1, 2, 0}, {1, 4, 2}}}), 0);
    EXPECT_EQ(check_quantised({{{0.3f, 0.3f, 0.3f}, {0.3f, 0.3f, 0.3f}}}), 0);
    EXPECT_EQ(check_quantised({{{-1, -1, -1}, {0, 0, 0}}, {{0, 0, 0}, {1, 1, 1}}}), 0);
    // Denormal extents, and a box spanning almost the whole float range.
    const float tiny = std::numeric_limits<float>::denorm_min();
    EXPECT_EQ(check_quantised({{{0, 0, 0}, {3 * tiny, tiny, 0}}, {{tiny, 0, 0}, {2 * tiny, 5 * tiny, tiny}}}), 0);
    const float big = 1e38f;
    EXPECT_EQ(check_quantised({{{-big, -big, -big}, {0, 1, 2}}, {{-1, -2, -3}, {big, big, big}}}), 0);
    // One ulp wide at a large coordinate: the grid's sums all round to two values.
    const float x = 1e7f, x1 = std::nextafter(x, 2e7f);
    EXPECT_EQ(check_quantised({{{x, x, x}, {x1, x, x1}}, {{x1, x1, x}, {x1, x1, x1}}}), 0);
}

// Small triangles far from the origin, whose boxes are a few ulps wide, and
// an axis-aligned grid of flat squares with rays grazing their planes: the
// cases where a decoded plane one rounding too far in would lose a hit.
TEST(BvhQuantise, BvhEqualsBruteForceWhereRoundingBites) {
    std::mt19937 rng(32);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    TriangleMesh far;
    const Vec3 base{3e5f, -2e5f, 1e5f};
    for (int i = 0; i < 3000; ++i) {
        const Vec3 c = base + Vec3{u(rng), u(rng), u(rng)} * 4.0f;
        const float s = 0.3f;
        add_triangle(far, c, c + Vec3{s * u(rng), s, 0}, c + Vec3{0, s * u(rng), s});
    }
    std::vector<Ray> rays;
    for (int i = 0; i < 4000; ++i) {
        Ray ray;
        ray.origin = base + Vec3{u(rng), u(rng), u(rng)} * 4.0f;
        ray.dir = normalize(Vec3{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f});
        ray.tmax = std::numeric_limits<float>::infinity();
        rays.push_back(ray);
    }
    Comparison c = compare_with_brute(far, rays);
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, 100);

    TriangleMesh grid;
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            const float x = 0.1f * static_cast<float>(i), y = 0.1f * static_cast<float>(j);
            add_triangle(grid, {x, y, 0}, {x + 0.1f, y, 0}, {x + 0.1f, y + 0.1f, 0});
            add_triangle(grid, {x, y, 0}, {x + 0.1f, y + 0.1f, 0}, {x, y + 0.1f, 0});
            add_triangle(grid, {x, 0, y}, {x + 0.1f, 0, y}, {x + 0.1f, 0, y + 0.1f});  // a second wall, y = 0
        }
    }
    rays.clear();
    for (int i = 0; i < 4000; ++i) {
        Ray ray;
        ray.origin = Vec3{4.0f * u(rng), 4.0f * u(rng), i % 2 == 0 ? 1e-3f * u(rng) : 1.0f};
        ray.dir = normalize(Vec3{u(rng) - 0.5f, u(rng) - 0.5f, i % 2 == 0 ? -1e-3f : -1.0f});
        ray.tmax = std::numeric_limits<float>::infinity();
        rays.push_back(ray);
    }
    c = compare_with_brute(grid, rays);
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, 1000);
}

}  // namespace
}  // namespace sombra
