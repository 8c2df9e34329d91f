#include "render/lights/spherical_triangle.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sombra {

namespace {

// The unit vector along a; false when a is (numerically) zero.
bool unit(Vec3d a, Vec3d& out) {
    const double len = length(a);
    if (!(len > 1e-300) || !std::isfinite(len)) return false;
    out = (1.0 / len) * a;
    return true;
}

// The component of v orthogonal to unit vector n, normalised (zero when v ∥ n).
Vec3d orthogonal_unit(Vec3d v, Vec3d n) {
    Vec3d out{0, 0, 0};
    unit(v - dot(v, n) * n, out);
    return out;
}

// The angle between unit vectors, robust near 0 and π.
double angle_between(Vec3d u, Vec3d v) {
    return dot(u, v) < 0 ? std::numbers::pi - 2.0 * std::asin(std::min(1.0, 0.5 * length(u + v)))
                         : 2.0 * std::asin(std::min(1.0, 0.5 * length(v - u)));
}

}  // namespace

SphericalTriangle make_spherical_triangle(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2) {
    SphericalTriangle t;
    const Vec3d o = to_double(x);
    Vec3d a, b, c;
    if (!unit(to_double(p0) - o, a) || !unit(to_double(p1) - o, b) || !unit(to_double(p2) - o, c)) return t;
    t.a = a;
    t.b = b;
    t.c = c;
    // Van Oosterom and Strackee's formula for the solid angle.
    const double triple = std::fabs(dot(a, cross(b, c)));
    const double omega = 2.0 * std::atan2(triple, 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
    // The angle at a between the great circles a→b and a→c.
    Vec3d n_ab, n_ac;
    if (!unit(cross(a, b), n_ab) || !unit(cross(a, c), n_ac) || !(omega > 0.0) || !std::isfinite(omega)) return t;
    t.alpha = angle_between(n_ab, n_ac);
    t.solid_angle = omega;
    return t;
}

Vec3 sample_spherical_triangle(const SphericalTriangle& t, float u1, float u2) {
    const Vec3d a = t.a, b = t.b, c = t.c;
    // Arvo: choose the sub-triangle (a, b, ĉ) of area u1·Ω, ĉ on the arc a→c …
    const double area = static_cast<double>(u1) * t.solid_angle;
    const double s = std::sin(area - t.alpha), tc = std::cos(area - t.alpha);
    const double cos_alpha = std::cos(t.alpha), sin_alpha = std::sin(t.alpha);
    const double u = tc - cos_alpha;
    const double v = s + sin_alpha * dot(a, b);  // cos of the side opposite c, the arc a–b
    const double denominator = (v * s + u * tc) * sin_alpha;
    double q = denominator != 0.0 ? ((v * tc - u * s) * cos_alpha - v) / denominator : 1.0;
    q = std::clamp(q, -1.0, 1.0);
    const Vec3d c_hat = q * a + std::sqrt(std::max(0.0, 1.0 - q * q)) * orthogonal_unit(c, a);
    // … then a point on the arc from b to ĉ, uniform in the remaining measure.
    const double z = 1.0 - static_cast<double>(u2) * (1.0 - dot(c_hat, b));
    const Vec3d d = z * b + std::sqrt(std::max(0.0, 1.0 - z * z)) * orthogonal_unit(c_hat, b);
    return to_float(d);
}

}  // namespace sombra
