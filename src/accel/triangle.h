// Möller–Trumbore ray/triangle intersection (Möller & Trumbore 1997), in the
// form with the geometric normal precomputed (as Embree's Moeller intersector
// does): the same test, two cross products cheaper per ray, and a degenerate
// triangle shows up as a zero normal, which no ray can hit.
//
// Made watertight at edges and corners. Plain MT is not: it measures each
// barycentric relative to the triangle's own first corner, so two triangles
// sharing an edge compute that edge's weight with different float formulas,
// and rounding can make both slightly negative: the ray slips between them
// (shared/scenes/manylights.json, pixel (711, 420), did). Here the float test
// decides whenever it is sure; a weight that is negative but within a
// rigorous bound of float rounding error is re-decided in double precision
// from the edge's original corners, taken in an order that does not depend on
// the triangle, and accepted unless it is negative beyond that computation's
// own rounding bound. The test so accepts every ray that the exact test
// accepts (plus rays within double rounding of an edge), and exact
// barycentric tests leave no gap between triangles that share corners.
// (Not covered: a ray within rounding of parallel to a triangle, whose det
// may get the wrong sign, and triangles so small, under ~1e-12, that the
// float bound below underflows; both behave as plain MT.)
// A robust fallback only at the edges, in the spirit of Woop, Benthin and
// Wald, "Watertight Ray/Triangle Intersection" (JCGT 2013), which settles
// edge functions it cannot decide in float in double precision.
#pragma once

#include <cfloat>
#include <cmath>

#include "core/vec3.h"
#include "scene/mesh.h"

namespace sombra {

// A triangle (p0, p1, p2) prepared for intersection: its corners as given
// (the near-edge test needs the original values, which p0 + (p1 − p0) does
// not give back) and n = (p1 − p0) × (p2 − p0), the unnormalised geometric
// normal, |n| = twice the area. n is zero for a triangle that can never be
// hit: one with a non-finite corner, or one whose dot(n, n) is below FLT_MIN
// (collinear or repeated corners, or an area under ~1e-19) or overflows (an
// area over ~1e19). So a triangle that can be hit always has a normal that
// normalize() turns into a unit vector, never NaN or zero.
struct PreparedTriangle {
    Vec3 p0, p1, p2, n;
};

inline PreparedTriangle prepare_triangle(Vec3 p0, Vec3 p1, Vec3 p2) {
    PreparedTriangle tri{p0, p1, p2, {}};
    if (!is_finite(p0) || !is_finite(p1) || !is_finite(p2)) return tri;
    const Vec3 n = cross(p1 - p0, p2 - p0);
    const float n2 = dot(n, n);
    // The negated comparison also sends NaN (from overflow) to "degenerate".
    if (!(n2 >= FLT_MIN && n2 <= FLT_MAX)) return tri;
    tri.n = n;
    return tri;
}

// True when prepare_triangle found the triangle hittable.
inline bool is_hittable(const PreparedTriangle& tri) { return tri.n != Vec3{}; }

// The mesh's triangle `tri` prepared from the mesh's own corners: what the
// brute-force loop tests and what the BVH re-tests near an edge. A triangle
// with an out-of-range index gets n = 0 (never hit).
inline PreparedTriangle prepare_triangle(const TriangleMesh& mesh, const Index3& tri) {
    const std::size_t vertex_count = mesh.positions.size();
    if (tri[0] >= vertex_count || tri[1] >= vertex_count || tri[2] >= vertex_count) return {};
    return prepare_triangle(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
}

namespace detail {

// A strict order on points that does not depend on which triangle asks.
inline bool vertex_before(Vec3 a, Vec3 b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

// The edge function E(a, b) = d · ((a − o) × (b − o)) of the ray against the
// directed edge a → b, times −1 when `flip`, is ≥ 0 up to rounding: in
// double, as d · ((lo − o) × (hi − lo)) with (lo, hi) the endpoints in
// vertex_before order, so the two triangles sharing the edge compute the very
// same number (one negates it). The differences of floats are exact in
// double unless their exponents lie ~29 apart, the products of those exact;
// `bound` (16 units in the last place of the sum of the absolute terms, about
// twice the worst case) covers what rounding is left, so an edge the ray
// really passes on the inside (E exactly ≥ 0) is never rejected.
inline bool edge_inside(Vec3 o, Vec3 d, Vec3 a, Vec3 b, bool flip) {
    const bool swap = vertex_before(b, a);
    const Vec3 lo = swap ? b : a, hi = swap ? a : b;
    const double ax = double(lo.x) - double(o.x), ay = double(lo.y) - double(o.y), az = double(lo.z) - double(o.z);
    const double ex = double(hi.x) - double(lo.x), ey = double(hi.y) - double(lo.y), ez = double(hi.z) - double(lo.z);
    const double px = ay * ez, qx = az * ey, py = az * ex, qy = ax * ez, pz = ax * ey, qz = ay * ex;
    const double dx = d.x, dy = d.y, dz = d.z;
    const double e = dx * (px - qx) + dy * (py - qy) + dz * (pz - qz);
    const double bound =
        8.0 * DBL_EPSILON *
        (std::fabs(dx) * (std::fabs(px) + std::fabs(qx)) + std::fabs(dy) * (std::fabs(py) + std::fabs(qy)) +
         std::fabs(dz) * (std::fabs(pz) + std::fabs(qz)));
    return (swap != flip ? -e : e) >= -bound;
}

}  // namespace detail

// Clamps a hit's weights (u, v) of p1 and p2 so that u, v ≥ 0 and u + v ≤ 1
// (then u + v rounds to at most 1): what every backend does to a hit found
// within rounding of an edge. A NaN weight becomes 0.
inline void clamp_barycentrics(float& u, float& v) {
    u = u > 0.0f ? (u < 1.0f ? u : 1.0f) : 0.0f;
    v = v > 0.0f ? v : 0.0f;
    if (u + v > 1.0f) v = 1.0f - u;
}

// Intersects o + t·d with `tri`. On a hit with 0 < t < tmax, writes t and the
// barycentric weights (b1, b2) of p1 and p2 (p0's is 1 − b1 − b2) and returns
// true; otherwise returns false and leaves t, b1, b2 untouched. Both faces
// count. Points on an edge or corner count as inside, and the test is
// watertight (see the top of this file): a ray through a mesh's shared edge
// or corner hits at least one of the triangles there, possibly several (ties
// go to the closest t, then the lower index, in accel.h). A ray within
// rounding of an edge may be accepted with a weight a hair below 0 (or a sum
// above 1); b1, b2 are clamped so that b1, b2 ≥ 0 and b1 + b2 ≤ 1. Rays
// parallel to the plane and degenerate triangles never hit. Every value
// written is finite.
inline bool intersect_triangle(Vec3 o, Vec3 d, const PreparedTriangle& tri, float tmax, float& t, float& b1,
                               float& b2) {
    // det = e1 · (d × e2) of the textbook form, = −d · (e1 × e2).
    const float det = -dot(d, tri.n);
    if (!(det != 0.0f)) return false;
    const Vec3 e1 = tri.p1 - tri.p0, e2 = tri.p2 - tri.p0;
    const Vec3 tvec = o - tri.p0;
    const Vec3 c = cross(tvec, d);
    const float su = dot(e2, c);   // u·det = tvec · (d × e2)
    const float sv = -dot(e1, c);  // v·det = d · (tvec × e1)
    // The three weights times |det| (inside: all ≥ 0), tested before dividing.
    const bool neg = det < 0.0f;
    const float U = neg ? -su : su, V = neg ? -sv : sv;
    const float W = (neg ? -det : det) - U - V;
    const bool inside = U >= 0.0f && V >= 0.0f && W >= 0.0f;
    if (!inside) {
        // Beyond `band` below zero a float weight is surely negative:
        // rounding in tvec, e1, e2, n, the cross and dot products and W's
        // subtractions stays below ~130·2^-24 of M = |d|·|e|·(|tvec| + |e|)
        // (max norms; first-order error analysis); the band is 2^9·2^-24·M.
        // Comparisons with NaN fail, so NaN weights are misses.
        const float dm = max_component(abs(d));
        const float tm = max_component(abs(tvec));
        const float em = max_component(max(abs(e1), abs(e2)));
        const float band = 0x1p-15f * (dm * em * (tm + em));
        if (!(U >= -band && V >= -band && W >= -band)) return false;
    }
    const float inv_det = 1.0f / det;
    const float tt = dot(tvec, tri.n) * inv_det;  // = e2 · (tvec × e1) / det
    if (!(tt > 0.0f && tt < tmax)) return false;
    if (!inside) {
        // Near an edge: each negative weight is re-decided from that edge's
        // corners alone. u·det = E(p0, p2), v·det = E(p1, p0) and
        // w·det = E(p2, p1) in exact arithmetic; the weight is ≥ 0 when the
        // edge function has det's sign.
        if (U < 0.0f && !detail::edge_inside(o, d, tri.p0, tri.p2, neg)) return false;
        if (V < 0.0f && !detail::edge_inside(o, d, tri.p1, tri.p0, neg)) return false;
        if (W < 0.0f && !detail::edge_inside(o, d, tri.p2, tri.p1, neg)) return false;
    }
    // tt passed, so inv_det is finite and non-zero and u, v are not NaN. The
    // clamps act only on hits within rounding of an edge (or on overflow).
    float u = su * inv_det, v = sv * inv_det;
    clamp_barycentrics(u, v);
    t = tt;
    b1 = u;
    b2 = v;
    return true;
}

// The same test for a triangle given by its corners.
inline bool intersect_triangle(Vec3 o, Vec3 d, Vec3 p0, Vec3 p1, Vec3 p2, float tmax, float& t, float& b1, float& b2) {
    return intersect_triangle(o, d, prepare_triangle(p0, p1, p2), tmax, t, b1, b2);
}

}  // namespace sombra
