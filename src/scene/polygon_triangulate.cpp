// Polygon → triangles. The geometry is done in double, relative to corner 0,
// because OBJ polygons far from the origin (thousands of units) lose too many
// float bits for the orientation tests.
#include "scene/polygon_triangulate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/vec3d.h"

namespace sombra {
namespace {

Vec3d to_local(Vec3 p, Vec3 origin) {
    return {double(p.x) - double(origin.x), double(p.y) - double(origin.y), double(p.z) - double(origin.z)};
}

void append_fan(std::size_t n, std::vector<PolygonTriangle>& out) {
    for (std::uint32_t k = 1; k + 1 < n; ++k) out.push_back({0, k, k + 1});
}

// Projects the corners onto the plane perpendicular to the Newell normal, in a
// basis (e1, e2) with e1 × e2 = normal, so the polygon winds counter-clockwise
// in (u, v). Returns false when the polygon has no usable normal.
bool project_onto_newell_plane(std::span<const Vec3> corners, PolygonScratch& s) {
    const std::size_t n = corners.size();
    const Vec3 origin = corners[0];
    double nx = 0, ny = 0, nz = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3d a = to_local(corners[i], origin);
        const Vec3d b = to_local(corners[(i + 1) % n], origin);
        nx += (a.y - b.y) * (a.z + b.z);
        ny += (a.z - b.z) * (a.x + b.x);
        nz += (a.x - b.x) * (a.y + b.y);
    }
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0) || !std::isfinite(len)) return false;
    nx /= len, ny /= len, nz /= len;

    // e1 ⟂ normal, built from the axis least aligned with it.
    const double ax = std::fabs(nx), ay = std::fabs(ny), az = std::fabs(nz);
    Vec3d axis = ax <= ay && ax <= az ? Vec3d{1, 0, 0} : (ay <= az ? Vec3d{0, 1, 0} : Vec3d{0, 0, 1});
    Vec3d e1{ny * axis.z - nz * axis.y, nz * axis.x - nx * axis.z, nx * axis.y - ny * axis.x};
    const double e1_len = std::sqrt(e1.x * e1.x + e1.y * e1.y + e1.z * e1.z);
    e1 = {e1.x / e1_len, e1.y / e1_len, e1.z / e1_len};
    const Vec3d e2{ny * e1.z - nz * e1.y, nz * e1.x - nx * e1.z, nx * e1.y - ny * e1.x};

    s.u.resize(n);
    s.v.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3d p = to_local(corners[i], origin);
        s.u[i] = p.x * e1.x + p.y * e1.y + p.z * e1.z;
        s.v[i] = p.x * e2.x + p.y * e2.y + p.z * e2.z;
    }
    return true;
}

// Twice the signed area of the projected triangle (a, b, c); > 0 when counter-clockwise.
double orient(const PolygonScratch& s, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return (s.u[b] - s.u[a]) * (s.v[c] - s.v[a]) - (s.v[b] - s.v[a]) * (s.u[c] - s.u[a]);
}

// A fan from corner 0 covers the polygon without overlap when every fan
// triangle turns counter-clockwise (zero-area ones allowed) and together they
// sweep less than a full turn around corner 0.
bool fan_is_valid(const PolygonScratch& s, double area_eps) {
    const std::size_t n = s.u.size();
    double sweep = 0;
    for (std::uint32_t k = 1; k + 1 < n; ++k) {
        const double cross = orient(s, 0, k, k + 1);
        if (cross < -area_eps) return false;
        const double dot = (s.u[k] - s.u[0]) * (s.u[k + 1] - s.u[0]) + (s.v[k] - s.v[0]) * (s.v[k + 1] - s.v[0]);
        sweep += std::atan2(std::max(cross, 0.0), dot);
    }
    return sweep < 2 * std::numbers::pi - 1e-9;
}

bool same_point(const PolygonScratch& s, std::uint32_t a, std::uint32_t b) {
    return s.u[a] == s.u[b] && s.v[a] == s.v[b];
}

// Is corner k inside or on the counter-clockwise triangle (a, b, c)?
bool inside_triangle(const PolygonScratch& s, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t k) {
    return orient(s, a, b, k) >= 0 && orient(s, b, c, k) >= 0 && orient(s, c, a, k) >= 0;
}

void ear_clip(PolygonScratch& s, double area_eps, std::vector<PolygonTriangle>& out) {
    const auto n = static_cast<std::uint32_t>(s.u.size());
    s.prev.resize(n);
    s.next.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        s.prev[i] = (i + n - 1) % n;
        s.next[i] = (i + 1) % n;
    }
    auto clip = [&](std::uint32_t i) {
        const std::uint32_t p = s.prev[i], q = s.next[i];
        out.push_back({p, i, q});
        s.next[p] = q;
        s.prev[q] = p;
    };

    // An ear: a left-turning corner whose triangle holds no other corner.
    auto is_ear = [&](std::uint32_t i) {
        const std::uint32_t p = s.prev[i], q = s.next[i];
        if (orient(s, p, i, q) <= area_eps) return false;
        for (std::uint32_t k = s.next[q]; k != p; k = s.next[k]) {
            if (same_point(s, k, p) || same_point(s, k, i) || same_point(s, k, q)) continue;
            if (inside_triangle(s, p, i, q, k)) return false;
        }
        return true;
    };

    std::uint32_t i = 0;
    for (std::uint32_t remaining = n; remaining > 3; --remaining) {
        bool clipped = false;
        for (std::uint32_t tries = 0; tries < remaining; ++tries) {
            if (is_ear(i)) {
                const std::uint32_t q = s.next[i];
                clip(i);
                i = q;
                clipped = true;
                break;
            }
            i = s.next[i];
        }
        if (clipped) continue;
        // No proper ear (self-intersecting or degenerate outline): clip the
        // corner that turns most to the left, so the count stays n - 2.
        std::uint32_t best = i;
        double best_turn = -std::numeric_limits<double>::infinity();
        std::uint32_t k = i;
        for (std::uint32_t t = 0; t < remaining; ++t, k = s.next[k]) {
            const double turn = orient(s, s.prev[k], k, s.next[k]);
            if (turn > best_turn) best_turn = turn, best = k;
        }
        i = s.next[best];
        clip(best);
    }
    out.push_back({s.prev[i], i, s.next[i]});
}

}  // namespace

PolygonSplit triangulate_polygon(std::span<const Vec3> corners, PolygonScratch& scratch,
                                 std::vector<PolygonTriangle>& out) {
    const std::size_t n = corners.size();
    if (n < 3) return PolygonSplit::Fan;
    // A quad is always a fan (spec §9), whatever its shape.
    if (n <= 4 || !project_onto_newell_plane(corners, scratch)) {
        append_fan(n, out);
        return PolygonSplit::Fan;
    }
    double extent = 0;
    for (std::size_t i = 0; i < n; ++i) extent = std::max({extent, std::fabs(scratch.u[i]), std::fabs(scratch.v[i])});
    const double area_eps = 1e-12 * extent * extent;
    if (!std::isfinite(extent) || fan_is_valid(scratch, area_eps)) {
        append_fan(n, out);
        return PolygonSplit::Fan;
    }
    if (n > kMaxEarClipCorners) {
        append_fan(n, out);
        return PolygonSplit::OverlapFan;
    }
    ear_clip(scratch, area_eps, out);
    return PolygonSplit::EarClipped;
}

}  // namespace sombra
