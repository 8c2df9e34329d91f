// make_bvh: binned SAH build (Wald, "On fast construction of SAH-based bounding
// volume hierarchies", 2007) over an array of triangle references that is
// partitioned in place, subtrees above kParallelRefs built in parallel.
//
// Determinism: every decision depends only on the references of the node
// being split, and a subtree of n references writes only to node slots
// reserved for it in advance (a binary tree with n leaves or fewer has at most
// 2n − 1 nodes), so the tree is the same for any number of threads. A final
// depth-first pass packs the slots into the dense node array.
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

#include "accel/bvh.h"

namespace sombra {
namespace {

constexpr int kBins = 16;
// Subtrees with more references than this build their two halves in parallel.
constexpr std::uint32_t kParallelRefs = 10000;
// Median splits from 2^32 references down to kBvhMaxLeafSize take 29 levels.
static_assert(kBvhSahMaxDepth + 29 < kBvhMaxDepth, "traversal stacks must hold the deepest path");
// SAH costs, relative: one node visit (two box tests) against one triangle test.
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
// instead of chasing indices into the mesh.
struct PrimRef {
    Box box;
    std::uint32_t triangle = 0;
    // Twice the bounds' centroid (saves a multiply; only order matters).
    Vec3 centroid2() const { return box.bmin + box.bmax; }
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
    float cost = kInf;  // sum over both sides of half_area · count
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

    RefRange measure(std::uint32_t begin, std::uint32_t end) const {
        RefRange range{begin, end, {}, {}};
        for (std::uint32_t i = begin; i < end; ++i) {
            range.bounds.grow(refs[i].box);
            range.centroids.grow(refs[i].centroid2());
        }
        return range;
    }

    // Fills slots[node] for `range`. Its descendants, if any, go to slots
    // [free, free + 2·count − 2).
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
        const std::uint32_t right_free = left_free + 2 * left.count() - 2;
        auto build_left = [&] { build(free, left, left_free, depth + 1); };
        auto build_right = [&] { build(free + 1, right, right_free, depth + 1); };
        if (range.count() > kParallelRefs) {
            tbb::parallel_invoke(build_left, build_right);
        } else {
            build_left();
            build_right();
        }
    }

    // Reorders the range's references into two non-empty halves, or returns
    // false when the node should be a leaf.
    bool split(const RefRange& range, int depth, RefRange& left, RefRange& right) {
        const std::uint32_t count = range.count();
        if (count == 1) return false;
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
        const float leaf_cost = kIntersectionCost * static_cast<float>(count) * area;
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
        struct Bin {
            Box box;
            std::uint32_t count = 0;
        };
        std::array<std::array<Bin, kBins>, 3> bins{};
        const int nbins = bin_count(range.count());
        const Vec3 cmin = range.centroids.bmin;
        const Vec3 extent = range.centroids.bmax - cmin;
        Vec3 scale;
        for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0.0f ? static_cast<float>(nbins) / extent[a] : 0.0f;
        for (std::uint32_t i = range.begin; i < range.end; ++i) {
            const PrimRef& ref = refs[i];
            const Vec3 c = ref.centroid2();
            for (int a = 0; a < 3; ++a) {
                Bin& bin = bins[a][bin_of(c[a], cmin[a], scale[a], nbins)];
                bin.box.grow(ref.box);
                ++bin.count;
            }
        }
        Split best;
        for (int a = 0; a < 3; ++a) {
            if (!(extent[a] > 0.0f)) continue;
            // right_cost[b]: half_area · count of bins [b, nbins).
            std::array<float, kBins> right_cost{};
            Box right;
            std::uint32_t right_count = 0;
            for (int b = nbins - 1; b > 0; --b) {
                right.grow(bins[a][b].box);
                right_count += bins[a][b].count;
                right_cost[b] = right_count > 0 ? right.half_area() * static_cast<float>(right_count) : kInf;
            }
            Box left;
            std::uint32_t left_count = 0;
            for (int b = 1; b < nbins; ++b) {
                left.grow(bins[a][b - 1].box);
                left_count += bins[a][b - 1].count;
                if (left_count == 0) continue;
                const float cost = left.half_area() * static_cast<float>(left_count) + right_cost[b];
                if (cost < best.cost) best = Split{a, b, cost, {}, {}};
            }
        }
        if (best.axis >= 0) {
            for (int b = 0; b < nbins; ++b) (b < best.bin ? best.left_bounds : best.right_bounds).grow(bins[best.axis][b].box);
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
        for (;;) {
            while (i < j && goes_left(refs[i])) left.centroids.grow(refs[i++].centroid2());
            while (i < j && !goes_left(refs[j - 1])) right.centroids.grow(refs[--j].centroid2());
            if (i >= j) break;
            std::swap(refs[i], refs[j - 1]);  // now refs[i] goes left and refs[j - 1] right
            left.centroids.grow(refs[i++].centroid2());
            right.centroids.grow(refs[--j].centroid2());
        }
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

// The references of every triangle that can be hit, in mesh order.
std::vector<PrimRef> make_prim_refs(const TriangleMesh& mesh) {
    std::vector<PrimRef> refs;
    refs.reserve(mesh.triangles.size());
    const std::size_t vertex_count = mesh.positions.size();
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const Index3& tri = mesh.triangles[i];
        if (tri[0] >= vertex_count || tri[1] >= vertex_count || tri[2] >= vertex_count) continue;
        const Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
        if (!is_hittable(make_triangle_edges(p0, p1, p2))) continue;
        PrimRef ref;
        ref.box.grow(p0);
        ref.box.grow(p1);
        ref.box.grow(p2);
        ref.triangle = static_cast<std::uint32_t>(i);
        refs.push_back(ref);
    }
    return refs;
}

// Packs the sparse slots depth first, each pair of children adjacent and a
// left subtree right after its parent's pair.
std::vector<BvhNode> pack_nodes(const std::vector<BvhNode>& slots) {
    std::vector<BvhNode> nodes;
    nodes.reserve(slots.size());
    nodes.push_back(slots[0]);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> todo{{0u, 0u}};  // (slot, node)
    while (!todo.empty()) {
        const auto [slot, node] = todo.back();
        todo.pop_back();
        if (slots[slot].count > 0) continue;
        const std::uint32_t left_slot = slots[slot].left_or_first;
        const auto left = static_cast<std::uint32_t>(nodes.size());
        nodes[node].left_or_first = left;
        nodes.push_back(slots[left_slot]);
        nodes.push_back(slots[left_slot + 1]);
        todo.emplace_back(left_slot + 1, left + 1);
        todo.emplace_back(left_slot, left);
    }
    return nodes;
}

}  // namespace

Bvh make_bvh(const TriangleMesh& mesh) {
    Bvh bvh;
    std::vector<PrimRef> refs = make_prim_refs(mesh);
    if (refs.empty()) return bvh;
    const auto count = static_cast<std::uint32_t>(refs.size());

    std::vector<BvhNode> slots(2 * static_cast<std::size_t>(count) - 1);
    Builder builder{refs, slots};
    builder.build(0, builder.measure(0, count), 1, 0);
    bvh.nodes = pack_nodes(slots);

    bvh.triangle_order.resize(count);
    bvh.ordered_triangles.resize(count);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, count, 4096),
                      [&](const tbb::blocked_range<std::uint32_t>& range) {
                          for (std::uint32_t k = range.begin(); k < range.end(); ++k) {
                              const Index3& tri = mesh.triangles[refs[k].triangle];
                              bvh.triangle_order[k] = refs[k].triangle;
                              bvh.ordered_triangles[k] = make_triangle_edges(
                                  mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
                          }
                      });
    return bvh;
}

std::size_t bvh_memory_bytes(const Bvh& bvh) {
    return bvh.nodes.size() * sizeof(BvhNode) + bvh.triangle_order.size() * sizeof(std::uint32_t) +
           bvh.ordered_triangles.size() * sizeof(TriangleEdges);
}

}  // namespace sombra
