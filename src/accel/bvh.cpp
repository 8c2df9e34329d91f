// BVH traversal: iterative with a fixed stack; the eight child boxes of a
// node tested at once with AVX (in two halves with SSE), the children entered nearest first, and boxes
// pruned by the closest hit so far. Leaves are tested four triangles at a
// time (bvh_triangle4.h); lanes near an edge fall back to the scalar test.
#include <immintrin.h>

#include <cassert>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <utility>

#include "accel/accel.h"
#include "accel/bvh.h"
#include "accel/bvh_triangle4.h"
#include "accel/triangle.h"

namespace sombra {
namespace {

// The slab test rounds (1/d, b − o, and their product); scaling the exit
// distance by 1 + 2γ₃ (pbrt's bound, here rounded up to 4 ulp) keeps it
// conservative, so a hit the triangle test accepts on a box face, or a tie
// at exactly the closest t, is never culled.
constexpr float kBoxSlack = 1.0f + 4.0f * FLT_EPSILON;

// What the slab test needs of a ray, computed once per ray, each value in
// every lane: eight with AVX, four (the node in two halves) without.
#ifdef __AVX__
using Lanes = __m256;
inline Lanes set1(float v) { return _mm256_set1_ps(v); }
inline Lanes load(const float* p) { return _mm256_load_ps(p); }
inline Lanes sub(Lanes a, Lanes b) { return _mm256_sub_ps(a, b); }
inline Lanes mul(Lanes a, Lanes b) { return _mm256_mul_ps(a, b); }
inline Lanes max(Lanes a, Lanes b) { return _mm256_max_ps(a, b); }
inline Lanes min(Lanes a, Lanes b) { return _mm256_min_ps(a, b); }
inline int le_mask(Lanes a, Lanes b) { return _mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OQ)); }
inline void store(float* p, Lanes a) { _mm256_store_ps(p, a); }
constexpr int kLanes = 8;
#else
using Lanes = __m128;
inline Lanes set1(float v) { return _mm_set1_ps(v); }
inline Lanes load(const float* p) { return _mm_load_ps(p); }
inline Lanes sub(Lanes a, Lanes b) { return _mm_sub_ps(a, b); }
inline Lanes mul(Lanes a, Lanes b) { return _mm_mul_ps(a, b); }
inline Lanes max(Lanes a, Lanes b) { return _mm_max_ps(a, b); }
inline Lanes min(Lanes a, Lanes b) { return _mm_min_ps(a, b); }
inline int le_mask(Lanes a, Lanes b) { return _mm_movemask_ps(_mm_cmple_ps(a, b)); }
inline void store(float* p, Lanes a) { _mm_store_ps(p, a); }
constexpr int kLanes = 4;
#endif
static_assert(kBvhWidth % kLanes == 0);

struct BoxRay {
    Lanes ox, oy, oz;
    Lanes ix, iy, iz;  // 1/d: ±∞ for a zero component, with the zero's sign
    // Offsets into BvhWideNode::bounds of the near planes per axis (the far
    // plane's is the offset ^ kBvhWidth): a ray running towards −axis
    // enters through the max plane.
    int near_x, near_y, near_z;
};

BoxRay make_box_ray(const Ray& ray) {
    const Vec3 inv{1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z};
    constexpr int W = kBvhWidth;
    return {set1(ray.origin.x),
            set1(ray.origin.y),
            set1(ray.origin.z),
            set1(inv.x),
            set1(inv.y),
            set1(inv.z),
            std::signbit(inv.x) ? W : 0,
            std::signbit(inv.y) ? 3 * W : 2 * W,
            std::signbit(inv.z) ? 5 * W : 4 * W};
}

// Writes the distances at which the ray enters the child boxes within
// [0, tmax] to tnear[] and returns a bit mask of the children it enters.
// Near and far planes are picked by the direction's sign, so a slab whose
// plane holds the origin while d is zero along that axis gives NaN (0·∞);
// max(a, b) and min(a, b) (maxps, minps) return b when a is NaN, so that slab
// then constrains nothing, and a ray lying in a box face still enters the box.
inline int enter_children(const BvhWideNode& node, const BoxRay& r, float tmax, float* tnear) {
    int mask = 0;
    for (int h = 0; h < kBvhWidth; h += kLanes) {
        const float* b = node.bounds + h;
        const Lanes tx0 = mul(sub(load(b + r.near_x), r.ox), r.ix);
        const Lanes tx1 = mul(sub(load(b + (r.near_x ^ kBvhWidth)), r.ox), r.ix);
        const Lanes ty0 = mul(sub(load(b + r.near_y), r.oy), r.iy);
        const Lanes ty1 = mul(sub(load(b + (r.near_y ^ kBvhWidth)), r.oy), r.iy);
        const Lanes tz0 = mul(sub(load(b + r.near_z), r.oz), r.iz);
        const Lanes tz1 = mul(sub(load(b + (r.near_z ^ kBvhWidth)), r.oz), r.iz);
        const Lanes t0 = max(tz0, max(ty0, max(tx0, set1(0.0f))));
        const Lanes t1 = min(tz1, min(ty1, min(tx1, set1(tmax))));
        store(tnear + h, t0);
        mask |= le_mask(t0, mul(t1, set1(kBoxSlack))) << h;
    }
    return mask;
}

// A child to visit: an inner node (count 0) or a leaf.
struct StackEntry {
    std::uint32_t child;
    std::uint32_t count;
    float tnear;  // the box's entry distance when pushed: pruned on pop if beyond the closest hit
};

// Asks for the memory a child visited later will read: an inner node's four
// cache lines, or a leaf's first triangle block. Under incoherent rays most
// of these reads miss the caches; a child put on the stack is visited after
// its nearer siblings' subtrees, time enough for the lines to arrive.
inline void prefetch_child(const BvhWideNode* nodes, const TriangleBlock* blocks, std::uint32_t child,
                           std::uint32_t count) {
    const char* p =
        count > 0 ? reinterpret_cast<const char*>(blocks + child) : reinterpret_cast<const char*>(nodes + child);
    const int bytes = count > 0 ? static_cast<int>(sizeof(TriangleBlock)) : static_cast<int>(sizeof(BvhWideNode));
    for (int k = 0; k < bytes; k += 64) _mm_prefetch(p + k, _MM_HINT_T0);
    _mm_prefetch(p + bytes - 1, _MM_HINT_T0);  // a block need not start on a line
}

// Pushes the entered children (bits of `mask`) but the nearest onto the
// stack, farthest deepest, and returns the nearest: the next to visit. One
// child, the most common case, touches no stack; two take one compare;
// more are pushed and insertion-sorted where they lie on the stack.
inline StackEntry enter_nearest_first(const BvhWideNode& node, int mask, const float* tnear, StackEntry* stack,
                                      int& size, const BvhWideNode* nodes, const TriangleBlock* blocks) {
    const auto entry = [&](int i) { return StackEntry{node.child[i], node.count[i], tnear[i]}; };
    StackEntry nearest = entry(__builtin_ctz(static_cast<unsigned>(mask)));
    mask &= mask - 1;
    if (mask == 0) return nearest;
    StackEntry other = entry(__builtin_ctz(static_cast<unsigned>(mask)));
    mask &= mask - 1;
    if (other.tnear < nearest.tnear) std::swap(nearest, other);
    if (mask == 0) {
        prefetch_child(nodes, blocks, other.child, other.count);
        stack[size++] = other;
        return nearest;
    }
    assert(size + __builtin_popcount(static_cast<unsigned>(mask)) + 2 <= kBvhStackSize);
    const int base = size;
    stack[size++] = other;
    stack[size++] = nearest;
    do {
        const StackEntry e = entry(__builtin_ctz(static_cast<unsigned>(mask)));
        mask &= mask - 1;
        int j = size++;
        for (; j > base && stack[j - 1].tnear < e.tnear; --j) stack[j] = stack[j - 1];
        stack[j] = e;
    } while (mask != 0);
    nearest = stack[--size];
    for (int j = base; j < size; ++j) prefetch_child(nodes, blocks, stack[j].child, stack[j].count);
    return nearest;
}

struct ClosestHit {
    float t, b1, b2;
    std::uint32_t triangle;
};

// Which candidate hits count. Without cut-outs every hit does, and the test
// compiles away; with them, surface_exists decides (scene/cutout.h).
struct EveryHit {
    static constexpr bool kFilters = false;
    bool keeps(std::uint32_t, float, float) const { return true; }
};
struct SurfaceHits {
    static constexpr bool kFilters = true;
    const Cutouts& cutouts;
    bool keeps(std::uint32_t triangle, float b1, float b2) const { return surface_exists(cutouts, triangle, b1, b2); }
};

template <typename Filter>
bool intersect_bvh_with(const Bvh& bvh, const Filter& filter, const Ray& ray, Hit& hit) {
    if (bvh.nodes.empty() || !is_traceable(ray)) return false;
    const BoxRay box_ray = make_box_ray(ray);
    const BvhWideNode* nodes = bvh.nodes.data();
    const TriangleBlock* blocks = bvh.blocks.data();
    const RayLanes lanes = make_ray_lanes(ray.origin, ray.dir);

    // The closest hit so far, in registers: assigning a whole Hit (its
    // corners zeroed) on each closer hit goes through the stack, and reading
    // it back stalls on store forwarding.
    ClosestHit best{ray.tmax, 0.0f, 0.0f, kNoHit};
    // Where the closest hit's corners lie: copied into `hit` once, at the end.
    const TriangleBlock* best_block = nullptr;
    int best_lane = 0;
    StackEntry stack[kBvhStackSize];
    int size = 0;
    StackEntry current{0, 0, 0.0f};
    for (;;) {
        if (current.count > 0) {
            const std::uint32_t end = current.child + (current.count + 3) / 4;
            for (std::uint32_t k = current.child; k < end; ++k) {
                const TriangleBlock& block = blocks[k];
                BlockHits found;
                intersect_block(block, lanes, ray.tmax, best.t, found);
                for (int sure = found.sure; sure != 0; sure &= sure - 1) {
                    const int lane = __builtin_ctz(static_cast<unsigned>(sure));
                    const float t = found.t[lane];
                    const std::uint32_t triangle = block.triangle[lane];
                    // Equal t: the lower index wins, as in the brute-force loop.
                    if (t < best.t || (t == best.t && triangle < best.triangle)) {
                        float b1, b2;
                        finish_barycentrics(found, lane, b1, b2);
                        if (!filter.keeps(triangle, b1, b2)) continue;
                        best = ClosestHit{t, b1, b2, triangle};
                        best_block = &block;
                        best_lane = lane;
                    }
                }
                for (int near = found.near; near != 0; near &= near - 1) {
                    const int lane = __builtin_ctz(static_cast<unsigned>(near));
                    const std::uint32_t triangle = block.triangle[lane];
                    float t, b1, b2;
                    if (!intersect_lane(block, lane, ray, t, b1, b2)) continue;
                    if ((t < best.t || (t == best.t && triangle < best.triangle)) && filter.keeps(triangle, b1, b2)) {
                        best = ClosestHit{t, b1, b2, triangle};
                        best_block = &block;
                        best_lane = lane;
                    }
                }
            }
        } else {
            const BvhWideNode& node = nodes[current.child];
            alignas(32) float tnear[kBvhWidth];
            const int mask = enter_children(node, box_ray, best.t, tnear);
            if (mask != 0) {
                current = enter_nearest_first(node, mask, tnear, stack, size, nodes, blocks);
                continue;
            }
        }
        // Pop the next box that may still hold something at or before the closest hit.
        for (;;) {
            if (size == 0) {
                if (best.triangle == kNoHit) return false;
                hit = Hit{best.t, best.b1, best.b2, best.triangle};
                hit.corners = block_corners(*best_block, best_lane);
                hit.has_corners = true;
                return true;
            }
            const StackEntry entry = stack[--size];
            if (entry.tnear <= best.t * kBoxSlack) {
                current = entry;
                break;
            }
        }
    }
}

// True when some lane of `found` that is sure of its hit keeps it.
template <typename Filter>
inline bool any_sure_hit_kept(const BlockHits& found, const TriangleBlock& block, const Filter& filter) {
    if constexpr (!Filter::kFilters) {
        return found.sure != 0;
    } else {
        for (int sure = found.sure; sure != 0; sure &= sure - 1) {
            const int lane = __builtin_ctz(static_cast<unsigned>(sure));
            float b1, b2;
            finish_barycentrics(found, lane, b1, b2);
            if (filter.keeps(block.triangle[lane], b1, b2)) return true;
        }
        return false;
    }
}

template <typename Filter>
bool occluded_bvh_with(const Bvh& bvh, const Filter& filter, const Ray& ray) {
    if (bvh.nodes.empty() || !is_traceable(ray)) return false;
    const BoxRay box_ray = make_box_ray(ray);
    const BvhWideNode* nodes = bvh.nodes.data();
    const TriangleBlock* blocks = bvh.blocks.data();
    const RayLanes lanes = make_ray_lanes(ray.origin, ray.dir);

    StackEntry stack[kBvhStackSize];
    int size = 0;
    StackEntry current{0, 0, 0.0f};
    for (;;) {
        if (current.count > 0) {
            const std::uint32_t end = current.child + (current.count + 3) / 4;
            for (std::uint32_t k = current.child; k < end; ++k) {
                BlockHits found;
                intersect_block(blocks[k], lanes, ray.tmax, ray.tmax, found);
                if (any_sure_hit_kept(found, blocks[k], filter)) return true;
                for (int near = found.near; near != 0; near &= near - 1) {
                    const int lane = __builtin_ctz(static_cast<unsigned>(near));
                    const std::uint32_t triangle = blocks[k].triangle[lane];
                    float t, b1, b2;
                    if (intersect_lane(blocks[k], lane, ray, t, b1, b2) && filter.keeps(triangle, b1, b2)) return true;
                }
            }
        } else {
            const BvhWideNode& node = nodes[current.child];
            alignas(32) float tnear[kBvhWidth];
            int mask = enter_children(node, box_ray, ray.tmax, tnear);
            if (mask != 0) {
                // Any order finds an occluder, and sorting costs more than it
                // saves here: slot order.
                const int first = __builtin_ctz(static_cast<unsigned>(mask));
                mask &= mask - 1;
                while (mask != 0) {
                    const int i = __builtin_ctz(static_cast<unsigned>(mask));
                    mask &= mask - 1;
                    assert(size < kBvhStackSize);
                    prefetch_child(nodes, blocks, node.child[i], node.count[i]);
                    stack[size++] = {node.child[i], node.count[i], 0.0f};
                }
                current = {node.child[first], node.count[first], 0.0f};
                continue;
            }
        }
        if (size == 0) return false;
        current = stack[--size];
    }
}

}  // namespace

bool intersect_bvh(const Bvh& bvh, const Ray& ray, Hit& hit) { return intersect_bvh_with(bvh, EveryHit{}, ray, hit); }

bool occluded_bvh(const Bvh& bvh, const Ray& ray) { return occluded_bvh_with(bvh, EveryHit{}, ray); }

bool intersect_bvh(const Bvh& bvh, const Cutouts& cutouts, const Ray& ray, Hit& hit) {
    return intersect_bvh_with(bvh, SurfaceHits{cutouts}, ray, hit);
}

bool occluded_bvh(const Bvh& bvh, const Cutouts& cutouts, const Ray& ray) {
    return occluded_bvh_with(bvh, SurfaceHits{cutouts}, ray);
}

}  // namespace sombra
