// Möller–Trumbore ray/triangle intersection (Möller & Trumbore 1997), in the
// form with the geometric normal precomputed (as Embree's Moeller intersector
// does): the same test, two cross products cheaper per ray, and a degenerate
// triangle shows up as a zero normal, which no ray can hit.
#pragma once

#include <cfloat>
#include <cmath>

#include "core/vec3.h"

namespace sombra {

// A triangle (p0, p1, p2) prepared for intersection: its first corner, its two
// edges from that corner and their cross product n = e1 × e2 (the unnormalised
// geometric normal, |n| = twice the area). n is zero for a triangle that can
// never be hit: one with a non-finite corner, or one whose dot(n, n) is below
// FLT_MIN (collinear or repeated corners, or an area under ~1e-19) or
// overflows (an area over ~1e19). So a triangle that can be hit always has a
// normal that normalize() turns into a unit vector, never NaN or zero.
struct TriangleEdges {
    Vec3 p0, e1, e2, n;
};

inline TriangleEdges make_triangle_edges(Vec3 p0, Vec3 p1, Vec3 p2) {
    TriangleEdges tri{p0, p1 - p0, p2 - p0, {}};
    if (!is_finite(p0) || !is_finite(p1) || !is_finite(p2)) return tri;
    const Vec3 n = cross(tri.e1, tri.e2);
    const float n2 = dot(n, n);
    // The negated comparison also sends NaN (from overflow) to "degenerate".
    if (!(n2 >= FLT_MIN && n2 <= FLT_MAX)) return tri;
    tri.n = n;
    return tri;
}

// True when make_triangle_edges found the triangle hittable.
inline bool is_hittable(const TriangleEdges& tri) { return tri.n != Vec3{}; }

// Intersects o + t·d with `tri`. On a hit with 0 < t < tmax, writes t and the
// barycentric weights (b1, b2) of p1 and p2 (p0's is 1 − b1 − b2) and returns
// true; otherwise returns false and leaves t, b1, b2 untouched. Both faces
// count. Points exactly on an edge or corner count as inside (b1 = 0, b2 = 0
// or b1 + b2 = 1). Rays parallel to the plane and degenerate triangles never
// hit. Every value written is finite: each one passed an ordered comparison,
// which NaN fails.
inline bool intersect_triangle(Vec3 o, Vec3 d, const TriangleEdges& tri, float tmax,
                               float& t, float& b1, float& b2) {
    // det = e1 · (d × e2) of the textbook form, = −d · (e1 × e2).
    const float det = -dot(d, tri.n);
    if (!(det != 0.0f)) return false;
    const float inv_det = 1.0f / det;
    const Vec3 tvec = o - tri.p0;
    const Vec3 c = cross(tvec, d);
    const float u = dot(tri.e2, c) * inv_det;   // = tvec · (d × e2) / det
    if (!(u >= 0.0f && u <= 1.0f)) return false;
    const float v = -dot(tri.e1, c) * inv_det;  // = d · (tvec × e1) / det
    if (!(v >= 0.0f && u + v <= 1.0f)) return false;
    const float tt = dot(tvec, tri.n) * inv_det;  // = e2 · (tvec × e1) / det
    if (!(tt > 0.0f && tt < tmax)) return false;
    t = tt;
    b1 = u;
    b2 = v;
    return true;
}

// The same test for a triangle given by its corners.
inline bool intersect_triangle(Vec3 o, Vec3 d, Vec3 p0, Vec3 p1, Vec3 p2, float tmax,
                               float& t, float& b1, float& b2) {
    return intersect_triangle(o, d, make_triangle_edges(p0, p1, p2), tmax, t, b1, b2);
}

}  // namespace sombra
