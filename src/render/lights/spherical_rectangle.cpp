#include "render/lights/spherical_rectangle.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sombra {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The angle whose cosine is c, c clamped to [−1, 1] against rounding.
double safe_acos(double c) { return std::acos(std::clamp(c, -1.0, 1.0)); }

}  // namespace

SphericalRectangle make_spherical_rectangle(Vec3 x, Vec3 corner, Vec3 edge1, Vec3 edge2) {
    SphericalRectangle r;
    const Vec3d e1 = to_double(edge1), e2 = to_double(edge2);
    const double len1 = length(e1), len2 = length(e2);
    if (!(len1 > 0.0) || !(len2 > 0.0) || !std::isfinite(len1) || !std::isfinite(len2)) return r;
    r.origin = to_double(x);
    r.ex = (1.0 / len1) * e1;
    r.ey = (1.0 / len2) * e2;
    r.ez = cross(r.ex, r.ey);
    const Vec3d d = to_double(corner) - r.origin;
    r.x0 = dot(d, r.ex);
    r.y0 = dot(d, r.ey);
    r.z0 = dot(d, r.ez);
    // The parametrisation wants the rectangle below the origin.
    if (r.z0 > 0.0) {
        r.z0 = -r.z0;
        r.ez = -1.0 * r.ez;
    }
    if (!(r.z0 < 0.0)) return r;  // x in the rectangle's plane: seen edge-on
    r.x1 = r.x0 + len1;
    r.y1 = r.y0 + len2;
    const double z0 = r.z0, z2 = z0 * z0;
    // Unit normals of the four planes through x and an edge (v00→v10,
    // v10→v11, v11→v01, v01→v00), in closed form, and the spherical
    // rectangle's interior angles between them (acos is cheaper here than
    // atan2 of the sums' sines and cosines).
    const double l0 = std::sqrt(z2 + r.y0 * r.y0), l1 = std::sqrt(z2 + r.x1 * r.x1);
    const double l2 = std::sqrt(z2 + r.y1 * r.y1), l3 = std::sqrt(z2 + r.x0 * r.x0);
    const Vec3d n0{0, z0 / l0, -r.y0 / l0}, n1{-z0 / l1, 0, r.x1 / l1};
    const Vec3d n2{0, -z0 / l2, r.y1 / l2}, n3{z0 / l3, 0, -r.x0 / l3};
    const double g0 = safe_acos(-dot(n0, n1)), g1 = safe_acos(-dot(n1, n2));
    const double g2 = safe_acos(-dot(n2, n3)), g3 = safe_acos(-dot(n3, n0));
    r.b0 = n0.z;
    r.b1 = n2.z;
    r.k = kTwoPi - g2 - g3;
    const double omega = g0 + g1 - r.k;
    if (!(omega > 0.0) || !std::isfinite(omega)) return r;
    r.solid_angle = omega;
    return r;
}

Vec3 sample_spherical_rectangle(const SphericalRectangle& r, float u1, float u2) {
    // u1 chooses the sub-rectangle [x0, xu] × [y0, y1] of solid angle u1·Ω …
    const double au = static_cast<double>(u1) * r.solid_angle + r.k;
    const double fu = (std::cos(au) * r.b0 - r.b1) / std::sin(au);
    const double cu = std::clamp(std::copysign(1.0, fu) / std::sqrt(fu * fu + r.b0 * r.b0), -1.0, 1.0);
    const double xu = std::clamp(-(cu * r.z0) / std::sqrt(std::max(1e-300, 1.0 - cu * cu)), r.x0, r.x1);
    // … and u2 a height along that edge's arc, uniform in the arc's measure.
    const double d = std::sqrt(xu * xu + r.z0 * r.z0);
    const double h0 = r.y0 / std::sqrt(d * d + r.y0 * r.y0), h1 = r.y1 / std::sqrt(d * d + r.y1 * r.y1);
    const double hv = h0 + static_cast<double>(u2) * (h1 - h0), hv2 = hv * hv;
    const double yv = hv2 < 1.0 - 1e-12 ? std::clamp(hv * d / std::sqrt(1.0 - hv2), r.y0, r.y1) : r.y1;
    return to_float(r.origin + xu * r.ex + yv * r.ey + r.z0 * r.ez);
}

}  // namespace sombra
