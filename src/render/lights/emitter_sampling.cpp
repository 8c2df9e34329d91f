#include "render/lights/emitter_sampling.h"

#include <algorithm>
#include <cmath>

#include "render/lights/spherical_rectangle.h"
#include "render/lights/spherical_triangle.h"

namespace sombra {

namespace {

// Triangles subtending a solid angle in this range (estimated first, see
// spherical_triangle_to_sample) are sampled uniformly over it (spherical
// triangles); outside it by area. Below the range d² and cos θ vary little
// over the triangle, so area sampling is nearly as good and cheaper. Near
// 2π sr (x almost on the triangle) Arvo's formulas lose precision.
constexpr double kMinSphericalSolidAngle = 0.05;
constexpr double kMaxSphericalSolidAngle = 6.0;

// Solid angles in which spherical sampling is used (after the estimate),
// for triangles and rectangles alike.
bool in_solid_angle_range(double omega) { return omega >= kMinSphericalSolidAngle && omega <= kMaxSphericalSolidAngle; }

// The spherical triangle of p0 p1 p2 seen from x when it is to be sampled by
// solid angle, or an empty one (solid angle 0: sampled by area). The choice
// is made on the solid angle estimated from the centroid c, area · |cos θ_c|
// / |x − c|², in float: building the spherical triangle (double precision,
// atan2, asin) only to decide would be paid at every shading point, though
// few sample by solid angle. Any choice that is a function of x and the
// triangle alone keeps the estimator unbiased, as long as sampling and
// density (sample_emitter_triangle, pdf_emitter_triangle) make the same one.
SphericalTriangle spherical_triangle_to_sample(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 unit_normal, float area) {
    const Vec3 to_x = x - (1.0f / 3.0f) * (p0 + p1 + p2);
    const float dist2 = dot(to_x, to_x);
    const float cos_area = std::fabs(dot(unit_normal, to_x)) * area;  // |cos θ_c| · area · |x − c|
    if (!(cos_area >= static_cast<float>(kMinSphericalSolidAngle) * dist2 * std::sqrt(dist2))) return {};
    return make_spherical_triangle(x, p0, p1, p2);
}

// Solid-angle density of area-uniform sampling of an emitter of `area`
// at the point `to_point` away from the shading point (dist2 = |to_point|²,
// dist its root, which the sampler has already taken for ω_i):
// pdf_area · d² / |cos θ_y|; 0 edge-on.
float area_density(Vec3 to_point, float dist2, float dist, Vec3 unit_normal, float area) {
    const float cos_y = std::fabs(dot(unit_normal, to_point)) / dist;
    if (!(cos_y > 0.0f)) return 0.0f;
    return dist2 / (cos_y * area);
}

// The same for point y seen from x.
float area_to_solid_angle(Vec3 x, Vec3 y, Vec3 unit_normal, float area) {
    const Vec3 d = y - x;
    const float dist2 = dot(d, d);
    if (!(dist2 > 0.0f)) return 0.0f;
    return area_density(d, dist2, std::sqrt(dist2), unit_normal, area);
}

// A rectangle is sampled by solid angle (render/lights/spherical_rectangle.h) where
// the triangles' rule (the estimated solid angle at least
// kMinSphericalSolidAngle) holds and sampling it by area would be far
// from that density: the area
// density's factor to solid angle, |cos θ_y|/d² = h/d³ (h the height of x
// over the plane), varies over the rectangle as (d_far/d_near)³, 64-fold
// from this ratio of squared distances on. Below it, sampling by area is
// far cheaper and nearly as good. Sampling and density make the same choice.
constexpr float kRectangleSolidAngleDistanceRatio2 = 16.0f;

// EmitterRectangle::solid_angle_reach2 for a rectangle of diagonal d. With
// the ratio k = d_far / d_near, d_far ≤ d_near + d gives d_near ≤ d/(k − 1),
// and the centre lies within d_near + d/2 of x: beyond that the ratio
// cannot be reached. 1 % more, so that rounding never turns away a point
// the full test would take.
float solid_angle_reach2(float diagonal) {
    const float k = std::sqrt(kRectangleSolidAngleDistanceRatio2);
    const float reach = 1.01f * diagonal * (1.0f / (k - 1.0f) + 0.5f);
    return reach * reach;
}

bool solid_angle_pays(Vec3 x, const EmitterRectangle& r) {
    const Vec3 from_centre = x - r.centre;
    const float dist2 = dot(from_centre, from_centre);
    // Most shading points are too far for the distance ratio below: one
    // comparison instead of the whole test.
    if (!(dist2 <= r.solid_angle_reach2)) return false;
    // The solid angle estimated from the centre, height · area / d³, at
    // least kMinSphericalSolidAngle, as for triangles; squared, so as to
    // need no root (a d³ past float's range is a far point: false).
    const float height_area = dot(from_centre, r.unit_normal) * r.area;
    constexpr auto kMin2 = static_cast<float>(kMinSphericalSolidAngle * kMinSphericalSolidAngle);
    if (!(height_area * height_area >= kMin2 * dist2 * dist2 * dist2)) return false;
    // The nearest and farthest points of the rectangle from x.
    const Vec3 d = x - r.corner;
    const float s = dot(d, r.edge1) * r.inv_length2_1, t = dot(d, r.edge2) * r.inv_length2_2;
    const Vec3 nearest = d - std::clamp(s, 0.0f, 1.0f) * r.edge1 - std::clamp(t, 0.0f, 1.0f) * r.edge2;
    const Vec3 farthest = d - (s < 0.5f ? 1.0f : 0.0f) * r.edge1 - (t < 0.5f ? 1.0f : 0.0f) * r.edge2;
    return dot(farthest, farthest) >= kRectangleSolidAngleDistanceRatio2 * dot(nearest, nearest);
}

}  // namespace

bool find_rectangle(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, EmitterRectangle& out) {
    int a_own = -1, b_own = -1, shared = 0;
    for (int i = 0; i < 3; ++i) {
        bool found = false;
        for (int j = 0; j < 3; ++j) found = found || a[i] == b[j];
        if (found)
            ++shared;
        else
            a_own = i;
    }
    for (int j = 0; j < 3; ++j)
        if (b[j] != a[0] && b[j] != a[1] && b[j] != a[2]) b_own = j;
    if (shared != 2 || a_own < 0 || b_own < 0) return false;
    const Vec3 q = a[a_own], u = a[(a_own + 1) % 3], v = a[(a_own + 2) % 3];
    const Vec3 e1 = u - q, e2 = v - q, normal = cross(e1, e2);
    const float l1 = length(e1), l2 = length(e2), area = length(normal);
    constexpr float kTolerance = 1e-5f;
    if (!(area > 0.0f) || !std::isfinite(area)) return false;
    if (!(std::fabs(dot(e1, e2)) <= kTolerance * l1 * l2)) return false;
    if (!(length(b[b_own] - (u + v - q)) <= kTolerance * (l1 + l2))) return false;
    if (!(dot(normal, cross(b[1] - b[0], b[2] - b[0])) > 0.0f)) return false;
    out.corner = q;
    out.edge1 = e1;
    out.edge2 = e2;
    out.unit_normal = normal / area;
    out.centre = q + 0.5f * (e1 + e2);
    out.area = area;
    out.inv_length2_1 = 1.0f / dot(e1, e1);
    out.inv_length2_2 = 1.0f / dot(e2, e2);
    out.solid_angle_reach2 = solid_angle_reach2(std::sqrt(l1 * l1 + l2 * l2));
    return true;
}

bool sample_emitter_triangle(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 n, float area, float u1, float u2, Vec3& y,
                             Vec3& wi, float& pdf) {
    const SphericalTriangle spherical = spherical_triangle_to_sample(x, p0, p1, p2, n, area);
    if (in_solid_angle_range(spherical.solid_angle)) {
        // Uniform over the solid angle; the point is where that direction meets the plane.
        wi = sample_spherical_triangle(spherical, u1, u2);
        const float t = dot(p0 - x, n) / dot(n, wi);
        if (!(t > 0.0f) || !std::isfinite(t)) return false;
        y = x + t * wi;
        pdf = static_cast<float>(1.0 / spherical.solid_angle);
        return true;
    }
    // Uniform by area: the square-root parameterisation of the triangle.
    const float su = std::sqrt(u1);
    const float b1 = 1.0f - su, b2 = u2 * su;
    y = (1.0f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
    const Vec3 to_light = y - x;
    const float dist2 = dot(to_light, to_light);
    if (!(dist2 > 0.0f)) return false;
    const float dist = std::sqrt(dist2);
    wi = to_light / dist;
    pdf = area_density(to_light, dist2, dist, n, area);
    return true;
}

float pdf_emitter_triangle(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 n, float area, Vec3 y) {
    const SphericalTriangle spherical = spherical_triangle_to_sample(x, p0, p1, p2, n, area);
    if (in_solid_angle_range(spherical.solid_angle)) return static_cast<float>(1.0 / spherical.solid_angle);
    return area_to_solid_angle(x, y, n, area);
}

bool sample_emitter_rectangle(const EmitterRectangle& r, Vec3 x, float u1, float u2, Vec3& y, Vec3& wi, float& pdf,
                              bool& in_near) {
    if (solid_angle_pays(x, r)) {
        const SphericalRectangle spherical = make_spherical_rectangle(x, r.corner, r.edge1, r.edge2);
        if (in_solid_angle_range(spherical.solid_angle)) {
            y = sample_spherical_rectangle(spherical, u1, u2);
            const Vec3 to_light = y - x;
            const float dist2 = dot(to_light, to_light);
            if (!(dist2 > 0.0f) || !is_finite(y)) return false;
            wi = to_light / std::sqrt(dist2);
            pdf = static_cast<float>(1.0 / spherical.solid_angle);
            const Vec3 d = y - r.corner;
            in_near = dot(d, r.edge1) * r.inv_length2_1 + dot(d, r.edge2) * r.inv_length2_2 <= 1.0f;
            return true;
        }
    }
    // By area.
    y = r.corner + u1 * r.edge1 + u2 * r.edge2;
    const Vec3 to_light = y - x;
    const float dist2 = dot(to_light, to_light);
    if (!(dist2 > 0.0f) || !is_finite(y)) return false;
    const float dist = std::sqrt(dist2);
    wi = to_light / dist;
    pdf = area_density(to_light, dist2, dist, r.unit_normal, r.area);
    if (!(pdf > 0.0f)) return false;
    in_near = u1 + u2 <= 1.0f;
    return true;
}

float pdf_emitter_rectangle(const EmitterRectangle& r, Vec3 x, Vec3 y) {
    if (solid_angle_pays(x, r)) {
        const double omega = make_spherical_rectangle(x, r.corner, r.edge1, r.edge2).solid_angle;
        if (in_solid_angle_range(omega)) return static_cast<float>(1.0 / omega);
    }
    return area_to_solid_angle(x, y, r.unit_normal, r.area);
}

}  // namespace sombra
