// BVH traversal: iterative with a fixed stack, both children's boxes tested,
// nearer first, pruned by the closest hit so far.
#include <cassert>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>

#include "accel/accel.h"
#include "accel/bvh.h"

namespace sombra {
namespace {

constexpr float kMiss = std::numeric_limits<float>::infinity();
// The slab test rounds (1/d, b − o, and their product); scaling the exit
// distance by 1 + 2γ₃ (pbrt's bound, here rounded up to 4 ulp) keeps it
// conservative, so a hit the triangle test accepts on a box face, or a tie
// at exactly the closest t, is never culled.
constexpr float kBoxSlack = 1.0f + 4.0f * FLT_EPSILON;

// What the slab test needs of a ray, computed once per ray.
struct BoxRay {
    Vec3 origin;
    Vec3 inv_dir;             // 1/d: ±∞ for a zero component, with the zero's sign
    bool neg_x, neg_y, neg_z;  // the ray runs towards −axis: it enters through bmax
};

BoxRay make_box_ray(const Ray& ray) {
    const Vec3 inv{1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z};
    return {ray.origin, inv, std::signbit(inv.x), std::signbit(inv.y), std::signbit(inv.z)};
}

// Distance to where the ray enters the node's box within [0, tmax], or kMiss.
// Near and far planes are picked by the direction's sign, so a slab whose
// plane holds the origin while d is zero along that axis gives NaN (0·∞), and
// `a > b ? a : b` / `a < b ? a : b` keep b when a is NaN: that slab then
// constrains nothing, and a ray lying in a box face still enters the box.
inline float box_entry(const BvhNode& node, const BoxRay& r, float tmax) {
    const float tx0 = ((r.neg_x ? node.bmax.x : node.bmin.x) - r.origin.x) * r.inv_dir.x;
    const float tx1 = ((r.neg_x ? node.bmin.x : node.bmax.x) - r.origin.x) * r.inv_dir.x;
    const float ty0 = ((r.neg_y ? node.bmax.y : node.bmin.y) - r.origin.y) * r.inv_dir.y;
    const float ty1 = ((r.neg_y ? node.bmin.y : node.bmax.y) - r.origin.y) * r.inv_dir.y;
    const float tz0 = ((r.neg_z ? node.bmax.z : node.bmin.z) - r.origin.z) * r.inv_dir.z;
    const float tz1 = ((r.neg_z ? node.bmin.z : node.bmax.z) - r.origin.z) * r.inv_dir.z;
    float tnear = tx0 > 0.0f ? tx0 : 0.0f;
    tnear = ty0 > tnear ? ty0 : tnear;
    tnear = tz0 > tnear ? tz0 : tnear;
    float tfar = tx1 < tmax ? tx1 : tmax;
    tfar = ty1 < tfar ? ty1 : tfar;
    tfar = tz1 < tfar ? tz1 : tfar;
    return tnear <= tfar * kBoxSlack ? tnear : kMiss;
}

// Rays that could only produce NaN or visit every box hit nothing.
bool is_traceable(const Ray& ray) {
    return is_finite(ray.origin) && is_finite(ray.dir) && ray.dir != Vec3{};
}

struct StackEntry {
    std::uint32_t node;
    float tnear;  // the box's entry distance when pushed: pruned on pop if beyond the closest hit
};

}  // namespace

bool intersect_bvh(const Bvh& bvh, const TriangleMesh& /*mesh*/, const Ray& ray, Hit& hit) {
    if (bvh.nodes.empty() || !is_traceable(ray)) return false;
    const BoxRay box_ray = make_box_ray(ray);
    const BvhNode* nodes = bvh.nodes.data();
    const TriangleEdges* triangles = bvh.ordered_triangles.data();

    Hit best;
    best.t = ray.tmax;
    if (box_entry(nodes[0], box_ray, best.t) == kMiss) return false;

    StackEntry stack[kBvhMaxDepth];
    int size = 0;
    std::uint32_t current = 0;
    for (;;) {
        const BvhNode& node = nodes[current];
        if (node.count > 0) {
            const std::uint32_t end = node.left_or_first + node.count;
            for (std::uint32_t k = node.left_or_first; k < end; ++k) {
                float t, b1, b2;
                if (!intersect_triangle(ray.origin, ray.dir, triangles[k], ray.tmax, t, b1, b2)) continue;
                const std::uint32_t triangle = bvh.triangle_order[k];
                // Equal t: the lower index wins, as in the brute-force loop.
                if (t < best.t || (t == best.t && triangle < best.triangle)) best = Hit{t, b1, b2, triangle};
            }
        } else {
            const std::uint32_t left = node.left_or_first;
            const float t_left = box_entry(nodes[left], box_ray, best.t);
            const float t_right = box_entry(nodes[left + 1], box_ray, best.t);
            if (t_left != kMiss && t_right != kMiss) {
                assert(size < kBvhMaxDepth);
                if (t_right < t_left) {
                    stack[size++] = {left, t_left};
                    current = left + 1;
                } else {
                    stack[size++] = {left + 1, t_right};
                    current = left;
                }
                continue;
            }
            if (t_left != kMiss) {
                current = left;
                continue;
            }
            if (t_right != kMiss) {
                current = left + 1;
                continue;
            }
        }
        // Pop the next box that may still hold something at or before the closest hit.
        for (;;) {
            if (size == 0) {
                if (best.triangle == kNoHit) return false;
                hit = best;
                return true;
            }
            const StackEntry entry = stack[--size];
            if (entry.tnear <= best.t * kBoxSlack) {
                current = entry.node;
                break;
            }
        }
    }
}

bool occluded_bvh(const Bvh& bvh, const TriangleMesh& /*mesh*/, const Ray& ray) {
    if (bvh.nodes.empty() || !is_traceable(ray)) return false;
    const BoxRay box_ray = make_box_ray(ray);
    const BvhNode* nodes = bvh.nodes.data();
    const TriangleEdges* triangles = bvh.ordered_triangles.data();
    if (box_entry(nodes[0], box_ray, ray.tmax) == kMiss) return false;

    std::uint32_t stack[kBvhMaxDepth];
    int size = 0;
    std::uint32_t current = 0;
    for (;;) {
        const BvhNode& node = nodes[current];
        if (node.count > 0) {
            const std::uint32_t end = node.left_or_first + node.count;
            for (std::uint32_t k = node.left_or_first; k < end; ++k) {
                float t, b1, b2;
                if (intersect_triangle(ray.origin, ray.dir, triangles[k], ray.tmax, t, b1, b2)) return true;
            }
        } else {
            const std::uint32_t left = node.left_or_first;
            const bool hit_left = box_entry(nodes[left], box_ray, ray.tmax) != kMiss;
            const bool hit_right = box_entry(nodes[left + 1], box_ray, ray.tmax) != kMiss;
            if (hit_left && hit_right) {
                assert(size < kBvhMaxDepth);
                stack[size++] = left + 1;
                current = left;
                continue;
            }
            if (hit_left || hit_right) {
                current = hit_left ? left : left + 1;
                continue;
            }
        }
        if (size == 0) return false;
        current = stack[--size];
    }
}

}  // namespace sombra
