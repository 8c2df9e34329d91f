// make_bvh: binned SAH build (Wald, "On fast construction of SAH-based bounding
// volume hierarchies", 2007) over an array of triangle references that is
// partitioned in place, subtrees above kParallelRefs built in parallel.
//
// Determinism: every decision depends only on the references of the node
// being split, and a subtree of n references writes only to node slots
// reserved for it in advance (a binary tree with n leaves or fewer has at most
// 2n − 1 nodes), so the tree is the same for any number of threads. The
// slots stay sparse: the collapse into the wide tree reads them as they are.
//
// Memory: the 2n − 1 slots are 64 bytes a triangle, but leaves of up to four
// references leave about two thirds of them unused. Subtrees built on one
// thread (kParallelRefs references or fewer, nearly all nodes) therefore
// take their slots in depth-first order from the start of their reserved
// range, and the slot array is left uninitialised: the unused tail of each
// range is never written, so its pages are never touched and cost no memory.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <immintrin.h>

#include "accel/bvh.h"
#include "accel/bvh_binary.h"

namespace sombra {
namespace {

constexpr int kBins = 32;
// Subtrees with more references than this build their two halves in parallel.
constexpr std::uint32_t kParallelRefs = 2048;
// Median splits from 2^32 references down to kBvhMaxLeafSize take 29 levels.
static_assert(kBvhSahMaxDepth + 29 < kBvhMaxDepth, "traversal stacks must hold the deepest path");
// SAH costs, relative: one node visit against one test of a block of four
// triangles (TriangleBlock: a leaf of 1 to 4 triangles costs the same).
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Box {
    Vec3 bmin{kInf};
    Vec3 bmax{-kInf};

    void grow(Vec3 p) { bmin = min(bmin, p); bmax = max(bmax, p); }
    void grow(const Box& b) { bmin = min(bmin, b.bmin); bmax = max(bmax, b.bmax); }
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
float blocks_of(std::uint32_t count) { return static_cast<float>((count + 3) / 4); }

// The bin of centroid coordinate c; NaN and overflow land in the end bins.
int bin_of(float c, float cmin, float scale, int bins) {
    const float f = (c - cmin) * scale;
    if (!(f > 0.0f)) return 0;
    return f < static_cast<float>(bins - 1) ? static_cast<int>(f) : bins - 1;
}

// Small nodes get fewer bins: about one per reference is resolution enough.
int bin_count(std::uint32_t refs) { return refs < kBins ? static_cast<int>(refs) : kBins; }

struct Builder {
    std::vector<PrimRef>& refs;
    BinaryNodeArray& slots;  // sparse and uninitialised: see the file comment

    RefRange measure(std::uint32_t begin, std::uint32_t end) const {
        BoxRows bounds, centroids;
        for (std::uint32_t i = begin; i < end; ++i) {
            const __m128 lo = refs[i].lo(), hi = refs[i].hi();
            bounds.grow(lo, hi);
            centroids.grow(_mm_add_ps(lo, hi));
        }
        return {begin, end, bounds.box(), centroids.box()};
    }

    // Fills slots[node] for `range`. Its descendants, if any, go to slots
    // [free, free + 2·count − 2).
    void build(std::uint32_t node, const RefRange& range, std::uint32_t free, int depth) {
        if (range.count() <= kParallelRefs) {
            std::uint32_t next = free;
            build_serial(node, range, next, depth);
            return;
        }
        RefRange left, right;
        if (!fill(node, range, depth, left, right, free)) return;
        const std::uint32_t left_free = free + 2;
        const std::uint32_t right_free = left_free + 2 * left.count() - 2;
        tbb::parallel_invoke([&] { build(free, left, left_free, depth + 1); },
                             [&] { build(free + 1, right, right_free, depth + 1); });
    }

    // build() on one thread: children take the next two slots from `next`,
    // depth first, so the subtree's slots are a prefix of its range.
    void build_serial(std::uint32_t node, const RefRange& range, std::uint32_t& next, int depth) {
        RefRange left, right;
        if (!fill(node, range, depth, left, right, next)) return;
        const std::uint32_t children = next;
        next += 2;
        build_serial(children, left, next, depth + 1);
        build_serial(children + 1, right, next, depth + 1);
    }

    // Writes slots[node]: a leaf (returns false), or an inner node whose
    // children go to slots `children` and `children` + 1, with the halves
    // of its references in `left` and `right`.
    bool fill(std::uint32_t node, const RefRange& range, int depth, RefRange& left, RefRange& right,
              std::uint32_t children) {
        BvhNode& out = slots[node];
        out.bmin = range.bounds.bmin;
        out.bmax = range.bounds.bmax;
        if (!split(range, depth, left, right)) {
            out.left_or_first = range.begin;
            out.count = range.count();
            return false;
        }
        out.left_or_first = children;
        out.count = 0;
        return true;
    }

    // Reorders the range's references into two non-empty halves, or returns
    // false when the node should be a leaf.
    bool split(const RefRange& range, int depth, RefRange& left, RefRange& right) {
        const std::uint32_t count = range.count();
        // One block's worth: the SAH below would choose a leaf anyway (a leaf
        // costs one block test, any split that plus a traversal step).
        if (count <= 4) return false;
        const bool may_be_leaf = count <= kBvhMaxLeafSize;
        if (depth >= kBvhSahMaxDepth) {
            if (may_be_leaf) return false;
            return median_split(range, left, right);
        }
        const Split best = find_sah_split(range);
        if (best.axis < 0) {  // all centroids coincide: no plane separates them
            if (may_be_leaf) return false;
            return median_split(range, left, right);
        }
        // Costs are scaled by the node's half area, which spares a division
        // (and a zero area gives "leaf", not NaN).
        const float area = range.bounds.half_area();
        const float leaf_cost = kIntersectionCost * blocks_of(count) * area;
        const float split_cost = kTraversalCost * area + kIntersectionCost * best.cost;
        if (may_be_leaf && leaf_cost <= split_cost) return false;

        partition(range, best, left, right);
        // Binning guarantees both sides are non-empty; stay safe regardless.
        if (left.count() == 0 || right.count() == 0) return median_split(range, left, right);
        return true;
    }

    // Bins the centroids along each axis and sweeps the bins once from each
    // side: the cheapest of the bins − 1 planes per axis in O(bins).
    Split find_sah_split(const RefRange& range) const {
        // Plain data, set up only for the nbins bins used: small nodes are
        // many, and 48 bins' constructors would cost them more than the binning.
        struct Bin {
            __m128 lo, hi;
            std::uint32_t count;
        };
        const int nbins = bin_count(range.count());
        Bin bins[3][kBins];
        for (auto& axis : bins) {
            for (int b = 0; b < nbins; ++b) axis[b] = {_mm_set1_ps(kInf), _mm_set1_ps(-kInf), 0};
        }
        const Vec3 cmin = range.centroids.bmin;
        const Vec3 extent = range.centroids.bmax - cmin;
        Vec3 scale;
        for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0.0f ? static_cast<float>(nbins) / extent[a] : 0.0f;
        // bin_of for the three axes at once, with the same float operations:
        // max(f, 0) sends NaN and f ≤ 0 to bin 0, min(·, nbins − 1) caps it.
        const __m128 cmin4 = _mm_setr_ps(cmin.x, cmin.y, cmin.z, 0.0f);
        const __m128 scale4 = _mm_setr_ps(scale.x, scale.y, scale.z, 0.0f);
        const __m128 top = _mm_set1_ps(static_cast<float>(nbins - 1));
        for (std::uint32_t i = range.begin; i < range.end; ++i) {
            const __m128 lo = refs[i].lo(), hi = refs[i].hi();
            const __m128 f = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(lo, hi), cmin4), scale4);
            alignas(16) std::int32_t bin[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(bin),
                            _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), top)));
            for (int a = 0; a < 3; ++a) {
                Bin& b = bins[a][bin[a]];
                b.lo = _mm_min_ps(b.lo, lo);
                b.hi = _mm_max_ps(b.hi, hi);
                ++b.count;
            }
        }
        Split best;
        for (int a = 0; a < 3; ++a) {
            if (!(extent[a] > 0.0f)) continue;
            // right_cost[b]: half_area · blocks of bins [b, nbins).
            float right_cost[kBins];
            BoxRows right;
            std::uint32_t right_count = 0;
            for (int b = nbins - 1; b > 0; --b) {
                right.grow(bins[a][b].lo, bins[a][b].hi);
                right_count += bins[a][b].count;
                right_cost[b] = right_count > 0 ? right.box().half_area() * blocks_of(right_count) : kInf;
            }
            BoxRows left;
            std::uint32_t left_count = 0;
            for (int b = 1; b < nbins; ++b) {
                left.grow(bins[a][b - 1].lo, bins[a][b - 1].hi);
                left_count += bins[a][b - 1].count;
                if (left_count == 0) continue;
                const float cost = left.box().half_area() * blocks_of(left_count) + right_cost[b];
                if (cost < best.cost) best = Split{a, b, cost, {}, {}};
            }
        }
        if (best.axis >= 0) {
            BoxRows l, r;
            for (int b = 0; b < nbins; ++b) (b < best.bin ? l : r).grow(bins[best.axis][b].lo, bins[best.axis][b].hi);
            best.left_bounds = l.box();
            best.right_bounds = r.box();
        }
        return best;
    }
    // Partitions in place by the split's plane, gathering each side's
    // centroid bounds on the way; each side's bounds are its bins' union.
    void partition(const RefRange& range, const Split& best, RefRange& left, RefRange& right) {
        const int axis = best.axis;
        const float cmin = range.centroids.bmin[axis];
        const int nbins = bin_count(range.count());
        const float scale = static_cast<float>(nbins) / (range.centroids.bmax[axis] - cmin);
        auto goes_left = [&](const PrimRef& r) { return bin_of(r.centroid2()[axis], cmin, scale, nbins) < best.bin; };
        left = RefRange{range.begin, range.begin, best.left_bounds, {}};
        right = RefRange{range.end, range.end, best.right_bounds, {}};
        std::uint32_t& i = left.end;
        std::uint32_t& j = right.begin;
        BoxRows left_centroids, right_centroids;
        auto centroid = [](const PrimRef& r) { return _mm_add_ps(r.lo(), r.hi()); };
        for (;;) {
            while (i < j && goes_left(refs[i])) left_centroids.grow(centroid(refs[i++]));
            while (i < j && !goes_left(refs[j - 1])) right_centroids.grow(centroid(refs[--j]));
            if (i >= j) break;
            std::swap(refs[i], refs[j - 1]);  // now refs[i] goes left and refs[j - 1] right
            left_centroids.grow(centroid(refs[i++]));
            right_centroids.grow(centroid(refs[--j]));
        }
        left.centroids = left_centroids.box();
        right.centroids = right_centroids.box();
    }

    // Splits at the middle reference after ordering by centroid along the
    // widest axis (or as they are, when every centroid is the same point).
    bool median_split(const RefRange& range, RefRange& left, RefRange& right) {
        const std::uint32_t mid = range.begin + range.count() / 2;
        const Vec3 extent = range.centroids.bmax - range.centroids.bmin;
        if (max_component(extent) > 0.0f) {
            const int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
            std::nth_element(refs.data() + range.begin, refs.data() + mid, refs.data() + range.end,
                             [axis](const PrimRef& a, const PrimRef& b) {
                                 const float ca = a.centroid2()[axis], cb = b.centroid2()[axis];
                                 return ca < cb || (ca == cb && a.triangle < b.triangle);
                             });
        }
        left = measure(range.begin, mid);
        right = measure(mid, range.end);
        return true;
    }
};

// The references of every triangle that can be hit, in mesh order: made in
// parallel (a triangle that cannot be hit gets triangle = its index + 1 as a
// mark), then compacted in order.
std::vector<PrimRef> make_prim_refs(const TriangleMesh& mesh) {
    const std::size_t count = mesh.triangles.size();
    const std::size_t vertex_count = mesh.positions.size();
    std::vector<PrimRef> all(count);
    std::vector<char> keep(count, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const Index3& tri = mesh.triangles[i];
            if (tri[0] >= vertex_count || tri[1] >= vertex_count || tri[2] >= vertex_count) continue;
            const Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
            if (!is_hittable(prepare_triangle(p0, p1, p2))) continue;
            all[i].bmin = min(p0, min(p1, p2));
            all[i].bmax = max(p0, max(p1, p2));
            all[i].triangle = static_cast<std::uint32_t>(i);
            keep[i] = 1;
        }
    });
    std::size_t kept = 0;
    for (std::size_t i = 0; i < count; ++i) {
        if (keep[i]) all[kept++] = all[i];
    }
    all.resize(kept);
    return all;
}

}  // namespace

BinaryBvh make_binary_bvh(const TriangleMesh& mesh) {
    BinaryBvh bvh;
    std::vector<PrimRef> refs = make_prim_refs(mesh);
    if (refs.empty()) return bvh;
    const auto count = static_cast<std::uint32_t>(refs.size());

    bvh.nodes.resize(2 * static_cast<std::size_t>(count) - 1);
    Builder builder{refs, bvh.nodes};
    builder.build(0, builder.measure(0, count), 1, 0);

    bvh.triangle_order.resize(count);
    for (std::uint32_t k = 0; k < count; ++k) bvh.triangle_order[k] = refs[k].triangle;
    return bvh;
}

}  // namespace sombra
