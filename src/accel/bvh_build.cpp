// make_bvh: binned SAH build (Wald, "On fast construction of SAH-based bounding
// volume hierarchies", 2007) over an array of triangle references that is
// partitioned in place, subtrees above kParallelRefs built in parallel.
//
// Determinism: every decision depends only on the references of the node
// being split, and a subtree of n references writes only to node slots
// reserved for it in advance (a binary tree with n leaves or fewer has at most
// 2n − 1 nodes), so the tree is the same for any number of threads. The
// slots stay sparse: the collapse into the wide tree reads them as they are.
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

// Box::half_area of three boxes at once (lanes 0–2; lane 3 unused), with
// the same float operations in the same order, so the tree does not change.
// The boxes must not be empty.
inline __m128 half_areas(const BoxRows (&boxes)[3]) {
    __m128 ex = _mm_sub_ps(boxes[0].hi, boxes[0].lo), ey = _mm_sub_ps(boxes[1].hi, boxes[1].lo);
    __m128 ez = _mm_sub_ps(boxes[2].hi, boxes[2].lo), unused = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(ex, ey, ez, unused);  // now lane a of ex is box a's x extent, and so on
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ex, ey), _mm_mul_ps(ey, ez)), _mm_mul_ps(ez, ex));
}

// half_area · blocks_of(count) per lane; infinite where count is 0 (the box
// is then empty and the product meaningless).
inline __m128 sah_term(__m128 half_area, __m128i count, __m128i three, __m128 inf) {
    const __m128 blocks = _mm_cvtepi32_ps(_mm_srli_epi32(_mm_add_epi32(count, three), 2));
    const __m128 empty = _mm_castsi128_ps(_mm_cmpeq_epi32(count, _mm_setzero_si128()));
    return _mm_blendv_ps(_mm_mul_ps(half_area, blocks), inf, empty);
}

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

// Small nodes get fewer bins: about one per reference is resolution enough.
int bin_count(std::uint32_t refs) { return refs < kBins ? static_cast<int>(refs) : kBins; }

struct Builder {
    std::vector<PrimRef>& refs;
    std::vector<BvhNode>& slots;  // sparse: see the file comment

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
    // side: the cheapest of the bins − 1 planes per axis in O(bins), the
    // three axes side by side in SSE lanes.
    Split find_sah_split(const RefRange& range) const {
        // Plain data, set up only for the nbins bins used: small nodes are
        // many, and 96 boxes' constructors would cost them more than the binning.
        struct Bin {
            __m128 lo, hi;
        };
        const int nbins = bin_count(range.count());
        Bin bins[3][kBins];
        alignas(16) std::int32_t counts[kBins][4];  // per bin, the count along axes x, y, z (lane 3 unused)
        for (int b = 0; b < nbins; ++b) {
            for (auto& axis : bins) axis[b] = {_mm_set1_ps(kInf), _mm_set1_ps(-kInf)};
            _mm_store_si128(reinterpret_cast<__m128i*>(counts[b]), _mm_setzero_si128());
        }
        const Vec3 cmin = range.centroids.bmin;
        const Vec3 extent = range.centroids.bmax - cmin;
        Vec3 scale;
        for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0.0f ? static_cast<float>(nbins) / extent[a] : 0.0f;
        // A doubled centroid c's bin along each axis, (c − cmin) · scale
        // truncated: max(f, 0) sends NaN and f ≤ 0 to bin 0, min(·, nbins − 1)
        // caps it. partition() bins with the same float operations.
        const __m128 cmin4 = _mm_setr_ps(cmin.x, cmin.y, cmin.z, 0.0f);
        const __m128 scale4 = _mm_setr_ps(scale.x, scale.y, scale.z, 0.0f);
        const __m128 top = _mm_set1_ps(static_cast<float>(nbins - 1));
        for (std::uint32_t i = range.begin; i < range.end; ++i) {
            const __m128 lo = refs[i].lo(), hi = refs[i].hi();
            const __m128 f = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(lo, hi), cmin4), scale4);
            const __m128i bin = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), top));
            const int bx = _mm_cvtsi128_si32(bin), by = _mm_extract_epi32(bin, 1), bz = _mm_extract_epi32(bin, 2);
            bins[0][bx].lo = _mm_min_ps(bins[0][bx].lo, lo);
            bins[0][bx].hi = _mm_max_ps(bins[0][bx].hi, hi);
            bins[1][by].lo = _mm_min_ps(bins[1][by].lo, lo);
            bins[1][by].hi = _mm_max_ps(bins[1][by].hi, hi);
            bins[2][bz].lo = _mm_min_ps(bins[2][bz].lo, lo);
            bins[2][bz].hi = _mm_max_ps(bins[2][bz].hi, hi);
            ++counts[bx][0];
            ++counts[by][1];
            ++counts[bz][2];
        }
        // Sweep from the right: right_cost[b], per axis lane, is half_area ·
        // blocks of bins [b, nbins), infinite while those bins are empty.
        const __m128 inf4 = _mm_set1_ps(kInf);
        const __m128i three = _mm_set1_epi32(3);
        __m128 right_cost[kBins];
        BoxRows right[3];
        __m128i right_count = _mm_setzero_si128();
        for (int b = nbins - 1; b > 0; --b) {
            for (int a = 0; a < 3; ++a) right[a].grow(bins[a][b].lo, bins[a][b].hi);
            right_count = _mm_add_epi32(right_count, _mm_load_si128(reinterpret_cast<const __m128i*>(counts[b])));
            right_cost[b] = sah_term(half_areas(right), right_count, three, inf4);
        }
        // Sweep from the left, keeping each axis's cheapest plane (the
        // lowest bin among equal costs, as a scalar sweep with `<` would).
        BoxRows left[3];
        __m128i left_count = _mm_setzero_si128();
        __m128 best_cost = inf4;
        __m128i best_bin = _mm_setzero_si128();
        for (int b = 1; b < nbins; ++b) {
            for (int a = 0; a < 3; ++a) left[a].grow(bins[a][b - 1].lo, bins[a][b - 1].hi);
            left_count = _mm_add_epi32(left_count, _mm_load_si128(reinterpret_cast<const __m128i*>(counts[b - 1])));
            const __m128 cost = _mm_add_ps(sah_term(half_areas(left), left_count, three, inf4), right_cost[b]);
            const __m128 better = _mm_cmplt_ps(cost, best_cost);
            best_cost = _mm_blendv_ps(best_cost, cost, better);
            best_bin = _mm_blendv_epi8(best_bin, _mm_set1_epi32(b), _mm_castps_si128(better));
        }
        alignas(16) float axis_cost[4];
        alignas(16) std::int32_t axis_bin[4];
        _mm_store_ps(axis_cost, best_cost);
        _mm_store_si128(reinterpret_cast<__m128i*>(axis_bin), best_bin);
        Split best;
        for (int a = 0; a < 3; ++a) {
            if (extent[a] > 0.0f && axis_cost[a] < best.cost) best = Split{a, axis_bin[a], axis_cost[a], {}, {}};
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
    // Block partitioning (Edelkamp and Weiß, "BlockQuicksort", 2016): which
    // side a reference goes to is a coin toss to the branch predictor, so
    // blocks of kBlock references from each end are classified without
    // branches and their misplaced references then swapped in pairs. The k-th
    // misplaced one from the left meets the k-th from the right, as in Hoare's
    // loop, which finishes the middle: the order is the same as Hoare's alone.
    void partition(const RefRange& range, const Split& best, RefRange& left, RefRange& right) {
        const int axis = best.axis;
        const float cmin = range.centroids.bmin[axis];
        const int nbins = bin_count(range.count());
        const float scale = static_cast<float>(nbins) / (range.centroids.bmax[axis] - cmin);
        const __m128 cmin4 = _mm_set1_ps(cmin), scale4 = _mm_set1_ps(scale);
        const __m128 top = _mm_set1_ps(static_cast<float>(nbins - 1));
        const __m128 inf4 = _mm_set1_ps(kInf), minus_inf4 = _mm_set1_ps(-kInf);
        const __m128i split_bin = _mm_set1_epi32(best.bin);
        const __m128i axis_lane = _mm_set1_epi32(axis);
        BoxRows left_centroids, right_centroids;
        // Whether r goes left (its bin by the binning's arithmetic, below the
        // split's); its doubled centroid grows that side's bounds, without a
        // branch (a reference classified twice grows them the same).
        auto goes_left = [&](const PrimRef& r) {
            const __m128 c = _mm_add_ps(r.lo(), r.hi());
            const __m128 f = _mm_mul_ps(_mm_sub_ps(c, cmin4), scale4);
            const __m128i bin = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), top));
            const __m128 is_left = _mm_permutevar_ps(_mm_castsi128_ps(_mm_cmplt_epi32(bin, split_bin)), axis_lane);
            left_centroids.grow(_mm_blendv_ps(inf4, c, is_left), _mm_blendv_ps(minus_inf4, c, is_left));
            right_centroids.grow(_mm_blendv_ps(c, inf4, is_left), _mm_blendv_ps(c, minus_inf4, is_left));
            return (_mm_movemask_ps(is_left) & 1) != 0;
        };
        // [begin, i) goes left, [j, end) right. Block offsets of misplaced
        // references: from i upwards on the left, from j − 1 downwards on the right.
        std::uint32_t i = range.begin, j = range.end;
        constexpr std::uint32_t kBlock = 64;
        std::uint8_t misplaced_left[kBlock], misplaced_right[kBlock];
        std::uint32_t left_count = 0, left_next = 0, right_count = 0, right_next = 0;
        while (j - i >= 2 * kBlock) {
            if (left_next == left_count) {
                left_count = left_next = 0;
                for (std::uint32_t k = 0; k < kBlock; ++k) {
                    misplaced_left[left_count] = static_cast<std::uint8_t>(k);
                    left_count += !goes_left(refs[i + k]);
                }
            }
            if (right_next == right_count) {
                right_count = right_next = 0;
                for (std::uint32_t k = 0; k < kBlock; ++k) {
                    misplaced_right[right_count] = static_cast<std::uint8_t>(k);
                    right_count += goes_left(refs[j - 1 - k]);
                }
            }
            const std::uint32_t pairs = std::min(left_count - left_next, right_count - right_next);
            for (std::uint32_t k = 0; k < pairs; ++k)
                std::swap(refs[i + misplaced_left[left_next + k]], refs[j - 1 - misplaced_right[right_next + k]]);
            left_next += pairs;
            right_next += pairs;
            if (left_next == left_count) i += kBlock;
            if (right_next == right_count) j -= kBlock;
        }
        // A block left with misplaced references resumes at the first of them.
        if (left_next < left_count) i += misplaced_left[left_next];
        if (right_next < right_count) j -= misplaced_right[right_next];
        for (;;) {
            while (i < j && goes_left(refs[i])) ++i;
            while (i < j && !goes_left(refs[j - 1])) --j;
            if (i >= j) break;
            std::swap(refs[i++], refs[--j]);  // refs[i] went right and refs[j - 1] left
        }
        left = RefRange{range.begin, i, best.left_bounds, left_centroids.box()};
        right = RefRange{j, range.end, best.right_bounds, right_centroids.box()};
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
