// make_bvh: binned SAH build (Wald, "On fast construction of SAH-based bounding
// volume hierarchies", 2007) over an array of triangle references that is
// partitioned in place, subtrees above kParallelRefs built in parallel; with
// BvhBuildOptions::spatial_splits, also spatial splits (bvh_spatial_split.h)
// where the object split's children overlap much.
//
// The reference array has room for the spatial splits' extra references: a
// node owns refs[begin, capacity_end), of which [begin, end) are in use, and
// a split shares its spare room out to the children in proportion to their
// references. So the budget is fixed at the root and memory cannot grow
// past it; with spatial splits off there is no spare room at all.
//
// Determinism: every decision depends only on the references of the node
// being split and its room, and a subtree with room for n references writes
// only to node slots reserved for it in advance (a binary tree with n
// leaves or fewer has at most 2n − 1 nodes), so the tree is the same for any
// number of threads. The slots stay sparse: the collapse into the wide tree
// reads them as they are.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <immintrin.h>

#include "accel/bvh.h"
#include "accel/bvh_binary.h"
#include "accel/bvh_build_refs.h"
#include "accel/bvh_spatial_split.h"

namespace sombra {
namespace {

using bvh_build::blocks_of;
using bvh_build::Box;
using bvh_build::BoxRows;
using bvh_build::kInf;
using bvh_build::PrimRef;
using bvh_build::RefRange;
using bvh_build::SpatialSplit;

constexpr int kBins = 32;
// Subtrees with more references than this build their two halves in parallel.
constexpr std::uint32_t kParallelRefs = 2048;
// Median splits from 2^32 references down to kBvhMaxLeafSize take 29 levels.
static_assert(kBvhSahMaxDepth + 29 < kBvhMaxDepth, "traversal stacks must hold the deepest path");
// SAH costs, relative: one node visit against one test of a block of four
// triangles (TriangleBlock: a leaf of 1 to 4 triangles costs the same).
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;

struct Split {
    int axis = -1;      // -1: no SAH split found
    int bin = 0;        // references in bins [0, bin) go left
    float cost = kInf;  // sum over both sides of half_area · blocks_of(count)
    Box left_bounds, right_bounds;
};

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
    std::vector<BvhNode>& slots;  // sparse: see the file comment
    const TriangleMesh& mesh;     // spatial splits clip against the triangles' corners
    bool spatial_splits = false;
    // Spatial splits are tried where the object split's children overlap by
    // more than this half area (α times the root's, Stich's criterion).
    float min_spatial_overlap = kInf;

    RefRange measure(std::uint32_t begin, std::uint32_t end) const {
        return bvh_build::measure_refs(refs.data(), begin, end);
    }

    // Fills slots[node] for `range`. Its descendants, if any, go to slots
    // [free, free + 2·capacity − 2).
    void build(std::uint32_t node, const RefRange& range, std::uint32_t free, int depth) {
        BvhNode& out = slots[node];
        out.bmin = range.bounds.bmin;
        out.bmax = range.bounds.bmax;
        RefRange left, right;
        if (!split(range, depth, left, right)) {
            out.left_or_first = range.begin;
            out.count = range.count();
            return;
        }
        out.left_or_first = free;
        out.count = 0;
        const std::uint32_t left_free = free + 2;
        const std::uint32_t right_free = left_free + 2 * left.capacity() - 2;
        auto build_left = [&] { build(free, left, left_free, depth + 1); };
        auto build_right = [&] { build(free + 1, right, right_free, depth + 1); };
        if (range.count() > kParallelRefs) {
            tbb::parallel_invoke(build_left, build_right);
        } else {
            build_left();
            build_right();
        }
    }

    // Reorders the range's references into two non-empty halves, each with
    // its share of the range's room, or returns false when the node should
    // be a leaf.
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
        SpatialSplit spatial;
        if (spatial_splits && range.spare() > 0 &&
            bvh_build::intersection(best.left_bounds, best.right_bounds).half_area() > min_spatial_overlap) {
            spatial = bvh_build::find_spatial_split(refs.data(), range, mesh);
        }
        // Costs are scaled by the node's half area, which spares a division
        // (and a zero area gives "leaf", not NaN).
        const float area = range.bounds.half_area();
        const float leaf_cost = kIntersectionCost * blocks_of(count) * area;
        const float split_cost = kTraversalCost * area + kIntersectionCost * std::min(best.cost, spatial.cost);
        if (may_be_leaf && leaf_cost <= split_cost) return false;

        if (spatial.cost < best.cost && spatial_partition(range, spatial, left, right)) return true;
        partition(range, best, left, right);
        // Binning guarantees both sides are non-empty; stay safe regardless.
        if (left.count() == 0 || right.count() == 0) return median_split(range, left, right);
        share_room(range, left, right);
        return true;
    }

    // Gives the children the range's spare room in proportion to their
    // references: the left keeps its place and room after it, the right's
    // references move up to start where that room ends.
    void share_room(const RefRange& range, RefRange& left, RefRange& right) {
        const std::uint64_t used = std::uint64_t{left.count()} + right.count();
        const std::uint64_t spare = range.capacity() - used;
        const auto left_room = static_cast<std::uint32_t>(spare * left.count() / used);
        left.capacity_end = left.end + left_room;
        const std::uint32_t right_count = right.count();
        if (right.begin != left.capacity_end) {
            std::memmove(refs.data() + left.capacity_end, refs.data() + right.begin, right_count * sizeof(PrimRef));
            right.begin = left.capacity_end;
            right.end = right.begin + right_count;
        }
        right.capacity_end = range.capacity_end;
    }

    // Applies a spatial split: the children's references are written after
    // each other into the range's room. False (references untouched) when a
    // side came out empty after unsplitting.
    bool spatial_partition(const RefRange& range, const SpatialSplit& split, RefRange& left, RefRange& right) {
        std::vector<PrimRef> left_refs, right_refs;
        left_refs.reserve(split.left_count);
        right_refs.reserve(split.right_count);
        bvh_build::partition_spatial(refs.data(), range, split, mesh, left_refs, right_refs);
        if (left_refs.empty() || right_refs.empty()) return false;
        const auto left_count = static_cast<std::uint32_t>(left_refs.size());
        const auto right_count = static_cast<std::uint32_t>(right_refs.size());
        std::copy(left_refs.begin(), left_refs.end(), refs.begin() + range.begin);
        std::copy(right_refs.begin(), right_refs.end(), refs.begin() + range.begin + left_count);
        left = measure(range.begin, range.begin + left_count);
        right = measure(left.end, left.end + right_count);
        share_room(range, left, right);
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
        left = RefRange{range.begin, range.begin, range.begin, best.left_bounds, {}};
        right = RefRange{range.end, range.end, range.end, best.right_bounds, {}};
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
        share_room(range, left, right);
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

BinaryBvh make_binary_bvh(const TriangleMesh& mesh, const BvhBuildOptions& options) {
    BinaryBvh bvh;
    std::vector<PrimRef> refs = make_prim_refs(mesh);
    if (refs.empty()) return bvh;
    const auto count = static_cast<std::uint32_t>(refs.size());
    // Room for the spatial splits' extra references, the budget; node slots
    // (2 per reference) must stay indexable by 32 bits.
    std::uint64_t capacity = count;
    if (options.spatial_splits && options.spatial_split_budget > 0.0f) {
        const auto extra = static_cast<std::uint64_t>(static_cast<double>(count) * options.spatial_split_budget);
        capacity = std::min<std::uint64_t>(count + extra, std::numeric_limits<std::uint32_t>::max() / 2);
        capacity = std::max<std::uint64_t>(capacity, count);
    }
    refs.resize(capacity);

    bvh.nodes.resize(2 * capacity - 1);
    Builder builder{refs, bvh.nodes, mesh};
    RefRange root = builder.measure(0, count);
    root.capacity_end = static_cast<std::uint32_t>(capacity);
    if (capacity > count) {
        builder.spatial_splits = true;
        builder.min_spatial_overlap = options.spatial_split_overlap * root.bounds.half_area();
    }
    builder.build(0, root, 1, 0);

    bvh.triangle_order.resize(capacity);
    for (std::size_t k = 0; k < capacity; ++k) bvh.triangle_order[k] = refs[k].triangle;
    return bvh;
}

}  // namespace sombra
