// What the binary builder (bvh_build.cpp) and its spatial splits
// (bvh_spatial_split.cpp) share: boxes, the triangle references they move
// around, and the SAH's block-counted cost. Internal to src/accel.
#pragma once

#include <cstdint>
#include <limits>

#include <immintrin.h>

#include "core/vec3.h"

namespace sombra::bvh_build {

inline constexpr float kInf = std::numeric_limits<float>::infinity();

struct Box {
    Vec3 bmin{kInf};
    Vec3 bmax{-kInf};

    void grow(Vec3 p) { bmin = min(bmin, p); bmax = max(bmax, p); }
    void grow(const Box& b) { bmin = min(bmin, b.bmin); bmax = max(bmax, b.bmax); }
    bool empty() const { return !(bmin.x <= bmax.x && bmin.y <= bmax.y && bmin.z <= bmax.z); }
    // Half the surface area: the SAH only compares areas. 0 for an empty box.
    float half_area() const {
        if (!(bmin.x <= bmax.x)) return 0.0f;
        const Vec3 e = bmax - bmin;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

inline Box intersection(const Box& a, const Box& b) { return {max(a.bmin, b.bmin), min(a.bmax, b.bmax)}; }

// One triangle to place, or with spatial splits one part of it: the box of
// that part and the triangle's index in the mesh. The in-place partition
// moves these small records, so binning reads them sequentially instead of
// chasing indices into the mesh. 32 bytes, aligned, so that each corner of
// the box loads as one SSE row (lane 3 is not used).
struct alignas(16) PrimRef {
    Vec3 bmin;
    std::uint32_t triangle = 0;
    Vec3 bmax;
    float unused = 0;
    Box box() const { return {bmin, bmax}; }
    // Twice the bounds' centroid (saves a multiply; only order matters).
    Vec3 centroid2() const { return bmin + bmax; }
    __m128 lo() const { return _mm_load_ps(&bmin.x); }
    __m128 hi() const { return _mm_load_ps(&bmax.x); }
};
static_assert(sizeof(PrimRef) == 32);

// A box as two SSE rows (lane 3 unused), grown with one min and one max.
struct BoxRows {
    __m128 lo = _mm_set1_ps(kInf);
    __m128 hi = _mm_set1_ps(-kInf);
    void grow(__m128 l, __m128 h) { lo = _mm_min_ps(lo, l); hi = _mm_max_ps(hi, h); }
    void grow(__m128 p) { grow(p, p); }
    Box box() const {
        alignas(16) float l[4], h[4];
        _mm_store_ps(l, lo);
        _mm_store_ps(h, hi);
        return {{l[0], l[1], l[2]}, {h[0], h[1], h[2]}};
    }
};

// A node's references, refs[begin, end), with their bounds and the bounds of
// their (doubled) centroids. refs[end, capacity_end) is spare room the
// node's subtree may fill with the extra references of spatial splits
// (empty when spatial splits are off).
struct RefRange {
    std::uint32_t begin = 0, end = 0, capacity_end = 0;
    Box bounds, centroids;
    std::uint32_t count() const { return end - begin; }
    std::uint32_t capacity() const { return capacity_end - begin; }
    std::uint32_t spare() const { return capacity_end - end; }
};

// The blocks of four that `count` triangles fill, as a cost factor: a leaf of
// 1 to 4 triangles costs one block test (TriangleBlock).
inline float blocks_of(std::uint32_t count) { return static_cast<float>((count + 3) / 4); }

// The bounds of refs[begin, end) and of their doubled centroids.
inline RefRange measure_refs(const PrimRef* refs, std::uint32_t begin, std::uint32_t end) {
    BoxRows bounds, centroids;
    for (std::uint32_t i = begin; i < end; ++i) {
        const __m128 lo = refs[i].lo(), hi = refs[i].hi();
        bounds.grow(lo, hi);
        centroids.grow(_mm_add_ps(lo, hi));
    }
    return {begin, end, end, bounds.box(), centroids.box()};
}

}  // namespace sombra::bvh_build
