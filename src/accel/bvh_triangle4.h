// intersect_triangle (triangle.h) for the four lanes of a TriangleBlock at
// once, with SSE. Each lane performs the scalar test's float operations in
// the same order (no FMA: the build sets -ffp-contract=off), so a lane the
// float test decides gives bit for bit the scalar result. Lanes the scalar
// test would send to its double-precision near-edge re-decision are not
// decided here but reported in `near`: the caller runs the scalar test on
// them. Internal to src/accel (bvh.cpp).
#pragma once

#include <immintrin.h>

#include <array>

#include "accel/bvh.h"
#include "accel/triangle.h"
#include "core/ray.h"

namespace sombra {

// The ray, broadcast to four lanes, and what the near-edge band needs of it.
struct RayLanes {
    __m128 ox, oy, oz, dx, dy, dz;
    __m128 dm;  // max_component(abs(d)), as the scalar band computes it
};

inline RayLanes make_ray_lanes(Vec3 o, Vec3 d) {
    return {_mm_set1_ps(o.x),
            _mm_set1_ps(o.y),
            _mm_set1_ps(o.z),
            _mm_set1_ps(d.x),
            _mm_set1_ps(d.y),
            _mm_set1_ps(d.z),
            _mm_set1_ps(max_component(abs(d)))};
}

// What intersect_block found. Lane i's bit in `sure` is set when the scalar
// test returns true with t = t[i] (0 < t < tmax) and weights from su[i],
// sv[i], inv_det[i] (finish_barycentrics); its bit in `near` when only the
// scalar test's double-precision edge test can decide, and the float t is
// in (0, tmax) and at or before near_limit. Lanes in neither are misses, or
// hits beyond near_limit.
struct BlockHits {
    int sure = 0;
    int near = 0;
    alignas(16) float t[4];
    alignas(16) float su[4];
    alignas(16) float sv[4];
    alignas(16) float inv_det[4];
};

namespace detail {
inline __m128 dot4(__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
}
inline __m128 abs4(__m128 a) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), a); }
}  // namespace detail

// The float part of intersect_triangle for the block's four lanes; `tmax`
// is the scalar test's tmax. Lanes the scalar test would re-decide near an
// edge are left out of `near` when their t exceeds `near_limit` (a closest
// hit so far: they could not beat it; pass tmax to keep them all). Fills t,
// su, sv, inv_det only when `sure` ≠ 0.
inline void intersect_block(const TriangleBlock& b, const RayLanes& r, float tmax, float near_limit, BlockHits& out) {
    using detail::dot4;
    const __m128 sign = _mm_set1_ps(-0.0f);
    const __m128 p0x = _mm_load_ps(b.p0[0]), p0y = _mm_load_ps(b.p0[1]), p0z = _mm_load_ps(b.p0[2]);
    // e1 = p1 − p0, e2 = p2 − p0, as prepare_triangle and intersect_triangle compute them.
    const __m128 e1x = _mm_sub_ps(_mm_load_ps(b.p1[0]), p0x), e1y = _mm_sub_ps(_mm_load_ps(b.p1[1]), p0y),
                 e1z = _mm_sub_ps(_mm_load_ps(b.p1[2]), p0z);
    const __m128 e2x = _mm_sub_ps(_mm_load_ps(b.p2[0]), p0x), e2y = _mm_sub_ps(_mm_load_ps(b.p2[1]), p0y),
                 e2z = _mm_sub_ps(_mm_load_ps(b.p2[2]), p0z);
    // n = cross(e1, e2), as prepare_triangle computes it.
    const __m128 nx = _mm_sub_ps(_mm_mul_ps(e1y, e2z), _mm_mul_ps(e1z, e2y));
    const __m128 ny = _mm_sub_ps(_mm_mul_ps(e1z, e2x), _mm_mul_ps(e1x, e2z));
    const __m128 nz = _mm_sub_ps(_mm_mul_ps(e1x, e2y), _mm_mul_ps(e1y, e2x));
    const __m128 det = _mm_xor_ps(dot4(r.dx, r.dy, r.dz, nx, ny, nz), sign);
    const __m128 nonzero = _mm_cmpneq_ps(det, _mm_setzero_ps());  // true for NaN, as !(det != 0) is false
    const __m128 tvx = _mm_sub_ps(r.ox, p0x);
    const __m128 tvy = _mm_sub_ps(r.oy, p0y);
    const __m128 tvz = _mm_sub_ps(r.oz, p0z);
    // c = cross(tvec, d)
    const __m128 cx = _mm_sub_ps(_mm_mul_ps(tvy, r.dz), _mm_mul_ps(tvz, r.dy));
    const __m128 cy = _mm_sub_ps(_mm_mul_ps(tvz, r.dx), _mm_mul_ps(tvx, r.dz));
    const __m128 cz = _mm_sub_ps(_mm_mul_ps(tvx, r.dy), _mm_mul_ps(tvy, r.dx));
    const __m128 su = dot4(e2x, e2y, e2z, cx, cy, cz);
    const __m128 sv = _mm_xor_ps(dot4(e1x, e1y, e1z, cx, cy, cz), sign);
    const __m128 flip = _mm_and_ps(_mm_cmplt_ps(det, _mm_setzero_ps()), sign);
    const __m128 U = _mm_xor_ps(su, flip), V = _mm_xor_ps(sv, flip);
    const __m128 W = _mm_sub_ps(_mm_sub_ps(_mm_xor_ps(det, flip), U), V);
    const __m128 zero = _mm_setzero_ps();
    // The least weight decides inside and the band. A NaN weight makes it
    // NaN, so that the lane fails both as the scalar test's comparisons do:
    // a NaN in U or V is one in W too, and minps returns its second operand
    // when either is NaN.
    const __m128 least = _mm_min_ps(_mm_min_ps(U, V), W);
    const __m128 inside = _mm_cmpge_ps(least, zero);
    const int inside_bits = _mm_movemask_ps(_mm_and_ps(inside, nonzero));
    const int outside_bits = _mm_movemask_ps(_mm_andnot_ps(inside, nonzero));
    out.sure = 0;
    out.near = 0;
    int within_bits = 0;
    if (outside_bits != 0) {
        // The scalar test's band, with its float operations in its order
        // (the power-of-two factor is exact), so a lane outside it here is
        // outside it there: a sure miss.
        using detail::abs4;
        const __m128 tm = _mm_max_ps(abs4(tvx), _mm_max_ps(abs4(tvy), abs4(tvz)));
        const __m128 em = _mm_load_ps(b.em);
        const __m128 band = _mm_mul_ps(_mm_set1_ps(0x1p-15f), _mm_mul_ps(_mm_mul_ps(r.dm, em), _mm_add_ps(tm, em)));
        within_bits = outside_bits & _mm_movemask_ps(_mm_cmpge_ps(least, _mm_xor_ps(band, sign)));
    }
    if ((inside_bits | within_bits) == 0) return;
    // t as the scalar test computes it, for the lanes inside and for those
    // within the band: the scalar test rejects the latter too when t is out
    // of (0, tmax), and the caller has no use for them beyond near_limit.
    const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
    const __m128 t = _mm_mul_ps(dot4(tvx, tvy, tvz, nx, ny, nz), inv_det);
    const __m128 in_range = _mm_and_ps(_mm_cmpgt_ps(t, zero), _mm_cmplt_ps(t, _mm_set1_ps(tmax)));
    const int in_range_bits = _mm_movemask_ps(in_range);
    out.near = within_bits & in_range_bits & _mm_movemask_ps(_mm_cmple_ps(t, _mm_set1_ps(near_limit)));
    out.sure = inside_bits & in_range_bits;
    if (out.sure == 0) return;
    _mm_store_ps(out.t, t);
    _mm_store_ps(out.su, su);
    _mm_store_ps(out.sv, sv);
    _mm_store_ps(out.inv_det, inv_det);
}

// The clamped weights (b1, b2) of a `sure` lane, as intersect_triangle
// computes them.
inline void finish_barycentrics(const BlockHits& h, int lane, float& b1, float& b2) {
    float u = h.su[lane] * h.inv_det[lane], v = h.sv[lane] * h.inv_det[lane];
    clamp_barycentrics(u, v);
    b1 = u;
    b2 = v;
}

// A lane's corners, the mesh's own (TriangleBlock).
inline std::array<Vec3, 3> block_corners(const TriangleBlock& b, int lane) {
    return {Vec3{b.p0[0][lane], b.p0[1][lane], b.p0[2][lane]}, Vec3{b.p1[0][lane], b.p1[1][lane], b.p1[2][lane]},
            Vec3{b.p2[0][lane], b.p2[1][lane], b.p2[2][lane]}};
}

// Re-decides a `near` lane: the scalar intersect_triangle on the lane's
// triangle, prepared from the corners the block holds (the mesh's own, so
// the same as the brute-force loop's), against `ray` up to ray.tmax.
inline bool intersect_lane(const TriangleBlock& b, int lane, const Ray& ray, float& t, float& b1, float& b2) {
    const std::array<Vec3, 3> p = block_corners(b, lane);
    const PreparedTriangle tri = prepare_triangle(p[0], p[1], p[2]);
    return intersect_triangle(ray.origin, ray.dir, tri, ray.tmax, t, b1, b2);
}

}  // namespace sombra
