// find_sah_split: binned SAH (Wald 2007). Each reference's doubled centroid
// goes into one of up to 32 bins per axis; one sweep from each side then
// costs every plane between bins, the three axes side by side in SSE lanes.
// Large nodes bin their references in parallel chunks, merged in chunk
// order: min, max and counts do not depend on the order, so the result is
// the same as one pass's.
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "accel/bvh_build_refs.h"

namespace sombra::bvh_build {

namespace {

// Box::half_area of three boxes at once (lanes 0–2; lane 3 unused), with
// the same float operations in the same order as the scalar formula.
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

// Where a doubled centroid c falls along each axis: (c − cmin) · scale
// truncated; max(f, 0) sends NaN and f ≤ 0 to bin 0, min(·, nbins − 1)
// caps it. partition_refs bins with the same float operations.
struct BinMap {
    __m128 cmin, scale, top;
};

// Plain data, set up only for the nbins bins used: small nodes are many,
// and 96 boxes' constructors would cost them more than the binning.
struct Bins {
    struct Box {
        __m128 lo, hi;
        void grow(__m128 l, __m128 h) {
            lo = _mm_min_ps(lo, l);
            hi = _mm_max_ps(hi, h);
        }
    };
    Box box[3][kBins];                         // per axis, per bin
    alignas(16) std::int32_t count[kBins][4];  // per bin, the count along axes x, y, z (lane 3 unused)

    void clear(int nbins) {
        for (int b = 0; b < nbins; ++b) {
            for (auto& axis : box) axis[b] = {_mm_set1_ps(kInf), _mm_set1_ps(-kInf)};
            _mm_store_si128(reinterpret_cast<__m128i*>(count[b]), _mm_setzero_si128());
        }
    }
    __m128i counts(int b) const { return _mm_load_si128(reinterpret_cast<const __m128i*>(count[b])); }
    void merge(const Bins& other, int nbins) {
        for (int b = 0; b < nbins; ++b) {
            for (int a = 0; a < 3; ++a) box[a][b].grow(other.box[a][b].lo, other.box[a][b].hi);
            _mm_store_si128(reinterpret_cast<__m128i*>(count[b]), _mm_add_epi32(counts(b), other.counts(b)));
        }
    }
};

void bin_refs(const PrimRef* refs, std::uint32_t begin, std::uint32_t end, const BinMap& map, Bins& bins) {
    for (std::uint32_t i = begin; i < end; ++i) {
        const __m128 lo = refs[i].lo(), hi = refs[i].hi();
        const __m128 f = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(lo, hi), map.cmin), map.scale);
        const __m128i bin = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), map.top));
        const int bx = _mm_cvtsi128_si32(bin), by = _mm_extract_epi32(bin, 1), bz = _mm_extract_epi32(bin, 2);
        bins.box[0][bx].grow(lo, hi);
        bins.box[1][by].grow(lo, hi);
        bins.box[2][bz].grow(lo, hi);
        ++bins.count[bx][0];
        ++bins.count[by][1];
        ++bins.count[bz][2];
    }
}

}  // namespace

Split find_sah_split(const PrimRef* refs, const RefRange& range) {
    const int nbins = bin_count(range.count());
    const Vec3 cmin = range.centroids.bmin;
    const Vec3 extent = range.centroids.bmax - cmin;
    Vec3 scale;
    for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0.0f ? static_cast<float>(nbins) / extent[a] : 0.0f;
    const BinMap map{_mm_setr_ps(cmin.x, cmin.y, cmin.z, 0.0f), _mm_setr_ps(scale.x, scale.y, scale.z, 0.0f),
                     _mm_set1_ps(static_cast<float>(nbins - 1))};
    Bins bins;
    bins.clear(nbins);
    if (range.count() <= kParallelPassRefs) {
        bin_refs(refs, range.begin, range.end, map, bins);
    } else {
        const std::uint32_t chunk = pass_chunk_size(range.count());
        const std::uint32_t chunks = (range.count() + chunk - 1) / chunk;
        std::vector<Bins> parts(chunks);
        tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, chunks, 1),
                          [&](const tbb::blocked_range<std::uint32_t>& r) {
                              for (std::uint32_t c = r.begin(); c < r.end(); ++c) {
                                  const std::uint32_t begin = range.begin + c * chunk;
                                  const std::uint32_t end = range.end - begin > chunk ? begin + chunk : range.end;
                                  parts[c].clear(nbins);
                                  bin_refs(refs, begin, end, map, parts[c]);
                              }
                          });
        for (const Bins& part : parts) bins.merge(part, nbins);
    }

    // Sweep from the right: right_cost[b], per axis lane, is half_area ·
    // blocks of bins [b, nbins), infinite while those bins are empty.
    const __m128 inf4 = _mm_set1_ps(kInf);
    const __m128i three = _mm_set1_epi32(3);
    __m128 right_cost[kBins];
    BoxRows right[3];
    __m128i right_count = _mm_setzero_si128();
    for (int b = nbins - 1; b > 0; --b) {
        for (int a = 0; a < 3; ++a) right[a].grow(bins.box[a][b].lo, bins.box[a][b].hi);
        right_count = _mm_add_epi32(right_count, bins.counts(b));
        right_cost[b] = sah_term(half_areas(right), right_count, three, inf4);
    }
    // Sweep from the left, keeping each axis's cheapest plane (the lowest
    // bin among equal costs, as a scalar sweep with `<` would).
    BoxRows left[3];
    __m128i left_count = _mm_setzero_si128();
    __m128 best_cost = inf4;
    __m128i best_bin = _mm_setzero_si128();
    for (int b = 1; b < nbins; ++b) {
        for (int a = 0; a < 3; ++a) left[a].grow(bins.box[a][b - 1].lo, bins.box[a][b - 1].hi);
        left_count = _mm_add_epi32(left_count, bins.counts(b - 1));
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
        for (int b = 0; b < nbins; ++b)
            (b < best.bin ? l : r).grow(bins.box[best.axis][b].lo, bins.box[best.axis][b].hi);
        best.left_bounds = l.box();
        best.right_bounds = r.box();
    }
    return best;
}

}  // namespace sombra::bvh_build
