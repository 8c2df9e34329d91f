#include "render/spherical_triangle.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sombra {

namespace {

struct D3 {
    double x, y, z;
};
D3 load(const double v[3]) { return {v[0], v[1], v[2]}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(D3 a) { return std::sqrt(dot(a, a)); }

// The unit vector along a; false when a is (numerically) zero.
bool unit(D3 a, D3& out) {
    const double len = length(a);
    if (!(len > 1e-300) || !std::isfinite(len)) return false;
    out = (1.0 / len) * a;
    return true;
}

// The component of v orthogonal to unit vector n, normalised (zero when v ∥ n).
D3 orthogonal_unit(D3 v, D3 n) {
    D3 out{0, 0, 0};
    unit(v - dot(v, n) * n, out);
    return out;
}

// The angle between unit vectors, robust near 0 and π.
double angle_between(D3 u, D3 v) {
    return dot(u, v) < 0 ? std::numbers::pi - 2.0 * std::asin(std::min(1.0, 0.5 * length(u + v)))
                         : 2.0 * std::asin(std::min(1.0, 0.5 * length(v - u)));
}

}  // namespace

SphericalTriangle make_spherical_triangle(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2) {
    SphericalTriangle t;
    const D3 o{x.x, x.y, x.z};
    D3 a, b, c;
    if (!unit(D3{p0.x, p0.y, p0.z} - o, a) || !unit(D3{p1.x, p1.y, p1.z} - o, b) || !unit(D3{p2.x, p2.y, p2.z} - o, c))
        return t;
    t.a[0] = a.x, t.a[1] = a.y, t.a[2] = a.z;
    t.b[0] = b.x, t.b[1] = b.y, t.b[2] = b.z;
    t.c[0] = c.x, t.c[1] = c.y, t.c[2] = c.z;
    // Van Oosterom and Strackee's formula for the solid angle.
    const double triple = std::fabs(dot(a, cross(b, c)));
    const double omega = 2.0 * std::atan2(triple, 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
    // The angle at a between the great circles a→b and a→c.
    D3 n_ab, n_ac;
    if (!unit(cross(a, b), n_ab) || !unit(cross(a, c), n_ac) || !(omega > 0.0) || !std::isfinite(omega)) return t;
    t.alpha = angle_between(n_ab, n_ac);
    t.solid_angle = omega;
    return t;
}

Vec3 sample_spherical_triangle(const SphericalTriangle& t, float u1, float u2) {
    const D3 a = load(t.a), b = load(t.b), c = load(t.c);
    // Arvo: choose the sub-triangle (a, b, ĉ) of area u1·Ω, ĉ on the arc a→c …
    const double area = static_cast<double>(u1) * t.solid_angle;
    const double s = std::sin(area - t.alpha), tc = std::cos(area - t.alpha);
    const double cos_alpha = std::cos(t.alpha), sin_alpha = std::sin(t.alpha);
    const double u = tc - cos_alpha;
    const double v = s + sin_alpha * dot(a, b);  // cos of the side opposite c, the arc a–b
    const double denominator = (v * s + u * tc) * sin_alpha;
    double q = denominator != 0.0 ? ((v * tc - u * s) * cos_alpha - v) / denominator : 1.0;
    q = std::clamp(q, -1.0, 1.0);
    const D3 c_hat = q * a + std::sqrt(std::max(0.0, 1.0 - q * q)) * orthogonal_unit(c, a);
    // … then a point on the arc from b to ĉ, uniform in the remaining measure.
    const double z = 1.0 - static_cast<double>(u2) * (1.0 - dot(c_hat, b));
    const D3 d = z * b + std::sqrt(std::max(0.0, 1.0 - z * z)) * orthogonal_unit(c_hat, b);
    return Vec3{static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)};
}

}  // namespace sombra
