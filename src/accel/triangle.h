// Möller–Trumbore ray/triangle intersection (Möller & Trumbore 1997).
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace sombra {

// Intersects o + t·d with triangle (p0, p1, p2). On a hit with 0 < t < tmax,
// writes t and the barycentric weights (b1, b2) of p1 and p2 and returns true.
// Both faces count. Degenerate (zero-area) triangles and rays parallel to the
// triangle's plane never hit, and never produce NaN.
inline bool intersect_triangle(Vec3 o, Vec3 d, Vec3 p0, Vec3 p1, Vec3 p2, float tmax,
                               float& t, float& b1, float& b2) {
    const Vec3 e1 = p1 - p0;
    const Vec3 e2 = p2 - p0;
    const Vec3 pvec = cross(d, e2);
    const float det = dot(e1, pvec);
    // det is 0 when d lies in the plane or the triangle has no area; the
    // negated test also rejects NaN.
    if (!(det != 0.0f)) return false;
    const float inv_det = 1.0f / det;
    const Vec3 tvec = o - p0;
    const float u = dot(tvec, pvec) * inv_det;
    if (!(u >= 0.0f && u <= 1.0f)) return false;
    const Vec3 qvec = cross(tvec, e1);
    const float v = dot(d, qvec) * inv_det;
    if (!(v >= 0.0f && u + v <= 1.0f)) return false;
    const float tt = dot(e2, qvec) * inv_det;
    if (!(tt > 0.0f && tt < tmax)) return false;
    t = tt;
    b1 = u;
    b2 = v;
    return true;
}

}  // namespace sombra
