// make_bvh: binned SAH build (Wald, "On fast construction of SAH-based bounding
// volume hierarchies", 2007) over an array of triangle references that is
// partitioned in place (bvh_build_refs.h: binning and partitioning, both in
// parallel chunks for large nodes), subtrees above kParallelRefs built in parallel.
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
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <immintrin.h>

#include "accel/bvh.h"
#include "accel/bvh_binary.h"
#include "accel/bvh_build_refs.h"

namespace sombra {
namespace {

using namespace bvh_build;

// Subtrees with more references than this build their two halves in parallel.
constexpr std::uint32_t kParallelRefs = 2048;
// Median splits from 2^32 references down to kBvhMaxLeafSize take 29 levels.
static_assert(kBvhSahMaxDepth + 29 < kBvhMaxDepth, "traversal stacks must hold the deepest path");
// SAH costs, relative: one node visit against one test of a block of four
// triangles (TriangleBlock: a leaf of 1 to 4 triangles costs the same).
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;

struct Builder {
    PrimRefArray& refs;
    BinaryNodeArray& slots;  // sparse and uninitialised: see the file comment

    // The range's bounds and centroid bounds; a large range (the root) in
    // parallel chunks, merged in chunk order.
    RefRange measure(std::uint32_t begin, std::uint32_t end) const {
        struct Bounds {
            BoxRows bounds, centroids;
        };
        auto measure_part = [&](std::uint32_t from, std::uint32_t to) {
            Bounds b;
            for (std::uint32_t i = from; i < to; ++i) {
                const __m128 lo = refs[i].lo(), hi = refs[i].hi();
                b.bounds.grow(lo, hi);
                b.centroids.grow(_mm_add_ps(lo, hi));
            }
            return b;
        };
        Bounds all;
        if (end - begin <= kParallelPassRefs) {
            all = measure_part(begin, end);
        } else {
            const std::uint32_t chunk = pass_chunk_size(end - begin);
            const std::uint32_t chunks = (end - begin + chunk - 1) / chunk;
            std::vector<Bounds> parts(chunks);
            tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, chunks, 1),
                              [&](const tbb::blocked_range<std::uint32_t>& r) {
                                  for (std::uint32_t c = r.begin(); c < r.end(); ++c) {
                                      const std::uint32_t from = begin + c * chunk;
                                      parts[c] = measure_part(from, end - from > chunk ? from + chunk : end);
                                  }
                              });
            for (const Bounds& part : parts) {
                all.bounds.grow(part.bounds);
                all.centroids.grow(part.centroids);
            }
        }
        return {begin, end, all.bounds.box(), all.centroids.box()};
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
        const Split best = find_sah_split(refs.data(), range);
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

        partition_refs(refs.data(), range, best, left, right);
        // Binning guarantees both sides are non-empty; stay safe regardless.
        if (left.count() == 0 || right.count() == 0) return median_split(range, left, right);
        return true;
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
// parallel, then compacted in order. The array is not zeroed first: its
// pages are first touched by the parallel pass (zeroing gigabytes on one
// thread, page faults included, would take seconds); entries of
// triangles that cannot be hit are never read.
PrimRefArray make_prim_refs(const TriangleMesh& mesh) {
    const std::size_t count = mesh.triangles.size();
    const std::size_t vertex_count = mesh.positions.size();
    PrimRefArray all(count);
    std::vector<char> keep(count, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const Index3& tri = mesh.triangles[i];
            if (tri[0] >= vertex_count || tri[1] >= vertex_count || tri[2] >= vertex_count) continue;
            const Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
            if (!is_hittable(prepare_triangle(p0, p1, p2))) continue;
            all[i] = PrimRef{min(p0, min(p1, p2)), static_cast<std::uint32_t>(i), max(p0, max(p1, p2)), 0.0f};
            keep[i] = 1;
        }
    });
    // Up to the first triangle left out, every entry is already in place.
    std::size_t kept = static_cast<std::size_t>(std::find(keep.begin(), keep.end(), 0) - keep.begin());
    for (std::size_t i = kept; i < count; ++i) {
        if (keep[i]) all[kept++] = all[i];
    }
    all.resize(kept);
    return all;
}

}  // namespace

BinaryBvh make_binary_bvh(const TriangleMesh& mesh) {
    BinaryBvh bvh;
    PrimRefArray refs = make_prim_refs(mesh);
    if (refs.empty()) return bvh;
    const auto count = static_cast<std::uint32_t>(refs.size());

    bvh.nodes.resize(2 * static_cast<std::size_t>(count) - 1);
    Builder builder{refs, bvh.nodes};
    builder.build(0, builder.measure(0, count), 1, 0);

    bvh.triangle_order.resize(count);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, count, 65536),
                      [&](const tbb::blocked_range<std::uint32_t>& r) {
                          for (std::uint32_t k = r.begin(); k < r.end(); ++k) bvh.triangle_order[k] = refs[k].triangle;
                      });
    return bvh;
}

}  // namespace sombra
