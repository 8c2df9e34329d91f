// The binned SAH build's parts (bvh_build.cpp): the triangle references it
// partitions in place, the boxes it grows with SSE, and the two passes over
// a node's references, binning (bvh_binning.cpp) and partitioning
// (bvh_partition.cpp). Internal to src/accel.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <immintrin.h>

#include "accel/bvh_binary.h"
#include "core/vec3.h"

namespace sombra::bvh_build {

inline constexpr int kBins = 32;
inline constexpr float kInf = std::numeric_limits<float>::infinity();
// Nodes with more references than this bin and partition them in parallel,
// in chunks whose bounds depend on the count alone, so that the tree is the
// same for any number of threads.
inline constexpr std::uint32_t kParallelPassRefs = 1u << 16;

struct Box {
    Vec3 bmin{kInf};
    Vec3 bmax{-kInf};

    void grow(Vec3 p) {
        bmin = min(bmin, p);
        bmax = max(bmax, p);
    }
    void grow(const Box& b) {
        bmin = min(bmin, b.bmin);
        bmax = max(bmax, b.bmax);
    }
    // Half the surface area: the SAH only compares areas. 0 for an empty box.
    float half_area() const {
        if (!(bmin.x <= bmax.x)) return 0.0f;
        const Vec3 e = bmax - bmin;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

// One triangle to place: its bounds and its index in the mesh. The in-place
// partition moves these small records, so binning reads them sequentially
// instead of chasing indices into the mesh. 32 bytes, aligned, so that each
// corner of the box loads as one SSE row (lane 3 is not used).
struct alignas(16) PrimRef {
    Vec3 bmin;
    std::uint32_t triangle = 0;
    Vec3 bmax;
    float unused = 0;
    // Twice the bounds' centroid (saves a multiply; only order matters).
    Vec3 centroid2() const { return bmin + bmax; }
    __m128 lo() const { return _mm_load_ps(&bmin.x); }
    __m128 hi() const { return _mm_load_ps(&bmax.x); }
};
static_assert(sizeof(PrimRef) == 32);
// Left unzeroed when made (bvh_build.cpp): every entry read is written first.
using PrimRefArray = std::vector<PrimRef, UninitialisedAllocator<PrimRef>>;

// A box as two SSE rows (lane 3 unused), grown with one min and one max.
struct BoxRows {
    __m128 lo = _mm_set1_ps(kInf);
    __m128 hi = _mm_set1_ps(-kInf);
    void grow(__m128 l, __m128 h) {
        lo = _mm_min_ps(lo, l);
        hi = _mm_max_ps(hi, h);
    }
    void grow(__m128 p) { grow(p, p); }
    void grow(const BoxRows& b) { grow(b.lo, b.hi); }
    Box box() const {
        alignas(16) float l[4], h[4];
        _mm_store_ps(l, lo);
        _mm_store_ps(h, hi);
        return {{l[0], l[1], l[2]}, {h[0], h[1], h[2]}};
    }
};

// A node's references, refs[begin, end), with their bounds and the bounds of
// their (doubled) centroids.
struct RefRange {
    std::uint32_t begin = 0, end = 0;
    Box bounds, centroids;
    std::uint32_t count() const { return end - begin; }
};

struct Split {
    int axis = -1;      // -1: no SAH split found
    int bin = 0;        // references in bins [0, bin) go left
    float cost = kInf;  // sum over both sides of half_area · blocks_of(count)
    Box left_bounds, right_bounds;
};

// The blocks of four that `count` triangles fill, as a cost factor.
inline float blocks_of(std::uint32_t count) {
    const std::uint32_t blocks = (count + 3) / 4;
    return static_cast<float>(blocks);
}

// Small nodes get fewer bins: about one per reference is resolution enough.
inline int bin_count(std::uint32_t refs) { return refs < kBins ? static_cast<int>(refs) : kBins; }

// The chunks a parallel pass cuts `count` references into: at least 16,384
// references each and at most 256 of them; a function of the count alone.
inline std::uint32_t pass_chunk_size(std::uint32_t count) {
    const std::uint32_t by_count = count / 256 + 1;
    return by_count > (1u << 14) ? by_count : (1u << 14);
}

// The cheapest binned SAH plane of the range (axis −1 when its centroids
// all coincide), with each side's bounds. bvh_binning.cpp.
Split find_sah_split(const PrimRef* refs, const RefRange& range);

// Reorders refs[range] so that the references left of the split's plane come
// first, and returns both sides with their bounds (from the split) and
// centroid bounds. bvh_partition.cpp.
void partition_refs(PrimRef* refs, const RefRange& range, const Split& split, RefRange& left, RefRange& right);

}  // namespace sombra::bvh_build
