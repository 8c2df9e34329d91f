// partition_refs: a node's references reordered in place by the split's
// plane, each side's centroid bounds gathered on the way.
//
// Within a range, block partitioning (Edelkamp and Weiß, "BlockQuicksort",
// 2016): which side a reference goes to is a coin toss to the branch
// predictor, so blocks of kBlock references from each end are classified
// without branches and their misplaced references then swapped in pairs.
// The k-th misplaced one from the left meets the k-th from the right, as in
// Hoare's loop, which finishes the middle: the order is Hoare's.
//
// A large node's range is cut into chunks (pass_chunk_size) partitioned in
// parallel; then the right-goers that lie where the left side will be are
// swapped, k-th with k-th in position order, with the left-goers that lie
// where the right side will be, in parallel again. The chunks depend on the
// count alone and each swap pairs fixed positions, so the order is the same
// for any number of threads.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "accel/bvh_build_refs.h"

namespace sombra::bvh_build {

namespace {

// Which side a reference goes to: its bin along the split's axis by the
// binning's own float operations (bvh_binning.cpp), below the split's bin.
struct Classifier {
    __m128 cmin, scale, top;
    __m128i split_bin, axis_lane;

    Classifier(const RefRange& range, const Split& split) {
        const int axis = split.axis;
        const float c = range.centroids.bmin[axis];
        const int nbins = bin_count(range.count());
        cmin = _mm_set1_ps(c);
        scale = _mm_set1_ps(static_cast<float>(nbins) / (range.centroids.bmax[axis] - c));
        top = _mm_set1_ps(static_cast<float>(nbins - 1));
        split_bin = _mm_set1_epi32(split.bin);
        axis_lane = _mm_set1_epi32(axis);
    }

    // Whether r goes left; its doubled centroid grows that side's bounds,
    // without a branch (a reference classified twice grows them the same).
    bool goes_left(const PrimRef& r, BoxRows& left, BoxRows& right) const {
        const __m128 c = _mm_add_ps(r.lo(), r.hi());
        const __m128 f = _mm_mul_ps(_mm_sub_ps(c, cmin), scale);
        const __m128i bin = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), top));
        const __m128 is_left = _mm_permutevar_ps(_mm_castsi128_ps(_mm_cmplt_epi32(bin, split_bin)), axis_lane);
        const __m128 inf = _mm_set1_ps(kInf), minus_inf = _mm_set1_ps(-kInf);
        left.grow(_mm_blendv_ps(inf, c, is_left), _mm_blendv_ps(minus_inf, c, is_left));
        right.grow(_mm_blendv_ps(c, inf, is_left), _mm_blendv_ps(c, minus_inf, is_left));
        return (_mm_movemask_ps(is_left) & 1) != 0;
    }
};

// One range's partition: [begin, mid) goes left, [mid, end) right.
struct SidesOf {
    std::uint32_t mid = 0;
    BoxRows left_centroids, right_centroids;
};

SidesOf partition_serial(PrimRef* refs, std::uint32_t begin, std::uint32_t end, const Classifier& side) {
    SidesOf out;
    auto goes_left = [&](const PrimRef& r) { return side.goes_left(r, out.left_centroids, out.right_centroids); };
    // [begin, i) goes left, [j, end) right. Block offsets of misplaced
    // references: from i upwards on the left, from j − 1 downwards on the right.
    std::uint32_t i = begin, j = end;
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
    out.mid = i;
    return out;
}

// Runs of references on the wrong side after the chunks are partitioned,
// in position order, with the count before each run.
struct Runs {
    std::vector<std::uint32_t> start, before;
    std::uint32_t total = 0;
    void add(std::uint32_t from, std::uint32_t to) {
        if (from >= to) return;
        start.push_back(from);
        before.push_back(total);
        total += to - from;
    }
    // The position of the k-th reference of the runs.
    std::uint32_t at(std::uint32_t k) const {
        const std::size_t run =
            static_cast<std::size_t>(std::upper_bound(before.begin(), before.end(), k) - before.begin()) - 1;
        return start[run] + (k - before[run]);
    }
};

SidesOf partition_parallel(PrimRef* refs, std::uint32_t begin, std::uint32_t end, const Classifier& side) {
    const std::uint32_t count = end - begin;
    const std::uint32_t chunk = pass_chunk_size(count);
    const std::uint32_t chunks = (count + chunk - 1) / chunk;
    auto chunk_end = [&](std::uint32_t c) { return end - (begin + c * chunk) > chunk ? begin + (c + 1) * chunk : end; };
    std::vector<SidesOf> parts(chunks);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, chunks, 1), [&](const tbb::blocked_range<std::uint32_t>& r) {
        for (std::uint32_t c = r.begin(); c < r.end(); ++c)
            parts[c] = partition_serial(refs, begin + c * chunk, chunk_end(c), side);
    });
    SidesOf out;
    std::uint32_t left_total = 0;
    for (std::uint32_t c = 0; c < chunks; ++c) {
        left_total += parts[c].mid - (begin + c * chunk);
        out.left_centroids.grow(parts[c].left_centroids);
        out.right_centroids.grow(parts[c].right_centroids);
    }
    out.mid = begin + left_total;
    // Right-goers before mid and left-goers from mid on: as many of each.
    Runs wrong_right, wrong_left;
    for (std::uint32_t c = 0; c < chunks; ++c) {
        const std::uint32_t first = begin + c * chunk, split = parts[c].mid, last = chunk_end(c);
        wrong_right.add(split, std::min(last, out.mid));
        wrong_left.add(std::max(first, out.mid), split);
    }
    constexpr std::uint32_t kSwapGrain = 1u << 12;
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, wrong_right.total, kSwapGrain),
                      [&](const tbb::blocked_range<std::uint32_t>& r) {
                          for (std::uint32_t k = r.begin(); k < r.end(); ++k)
                              std::swap(refs[wrong_right.at(k)], refs[wrong_left.at(k)]);
                      });
    return out;
}

}  // namespace

void partition_refs(PrimRef* refs, const RefRange& range, const Split& split, RefRange& left, RefRange& right) {
    const Classifier side(range, split);
    const SidesOf sides = range.count() > kParallelPassRefs ? partition_parallel(refs, range.begin, range.end, side)
                                                            : partition_serial(refs, range.begin, range.end, side);
    left = RefRange{range.begin, sides.mid, split.left_bounds, sides.left_centroids.box()};
    right = RefRange{sides.mid, range.end, split.right_bounds, sides.right_centroids.box()};
}

}  // namespace sombra::bvh_build
