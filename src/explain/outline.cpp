#include "explain/outline.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace sombra {

namespace {

// cos 35°: neighbours meeting at a sharper angle than this make a crease.
constexpr float kCreaseCos = 0.819f;

struct EdgeFaces {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    bool crease = false;
};

Vec3 face_normal(const TriangleMesh& mesh, std::size_t t) {
    const Index3& tri = mesh.triangles[t];
    const Vec3 n =
        cross(mesh.positions[tri[1]] - mesh.positions[tri[0]], mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    const float len = length(n);
    return len > 0.0f && std::isfinite(len) ? n / len : Vec3{0.0f};
}

float projected_length(Segment s, Vec3 view_dir) {
    const Vec3 d = s.b - s.a;
    return length(d - dot(d, view_dir) * view_dir);
}

}  // namespace

std::vector<Segment> box_segments(const TriangleMesh& mesh, std::size_t first, std::size_t count) {
    Vec3 lo{INFINITY}, hi{-INFINITY};
    for (std::size_t t = first; t < first + count && t < mesh.triangles.size(); ++t)
        for (const std::uint32_t v : mesh.triangles[t]) {
            if (v >= mesh.positions.size() || !is_finite(mesh.positions[v])) continue;
            lo = min(lo, mesh.positions[v]);
            hi = max(hi, mesh.positions[v]);
        }
    if (!(lo.x <= hi.x)) return {};
    auto corner = [&](int i) { return Vec3{i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z}; };
    std::vector<Segment> edges;
    for (int i = 0; i < 8; ++i)
        for (int bit = 1; bit < 8; bit <<= 1)
            if (!(i & bit)) edges.push_back({corner(i), corner(i | bit)});
    return edges;
}

std::vector<Segment> outline_segments(const TriangleMesh& mesh, Vec3 view_dir, std::size_t budget,
                                      std::size_t max_triangles) {
    if (mesh.triangles.size() > max_triangles) return box_segments(mesh, 0, mesh.triangles.size());

    std::unordered_map<std::uint64_t, EdgeFaces> edges;
    edges.reserve(mesh.triangles.size() * 2);
    std::vector<Vec3> normals(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        normals[t] = face_normal(mesh, t);
        if (normals[t] == Vec3{0.0f}) continue;  // degenerate: not a face to outline
        const Index3& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = std::min(tri[k], tri[(k + 1) % 3]), b = std::max(tri[k], tri[(k + 1) % 3]);
            EdgeFaces& e = edges[(std::uint64_t{a} << 32) | b];
            if (e.count == 0) {
                e.first = static_cast<std::uint32_t>(t);
            } else {
                const Vec3 n0 = normals[e.first], n1 = normals[t];
                // Creases, and silhouettes: one side faces the viewer, the other away.
                if (std::fabs(dot(n0, n1)) < kCreaseCos || (dot(n0, view_dir) > 0.0f) != (dot(n1, view_dir) > 0.0f))
                    e.crease = true;
            }
            ++e.count;
        }
    }

    std::vector<Segment> lines;
    for (const auto& [key, e] : edges) {
        if (e.count == 2 && !e.crease) continue;
        const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
        lines.push_back({mesh.positions[a], mesh.positions[b]});
    }
    if (lines.size() > budget) {
        std::nth_element(lines.begin(), lines.begin() + static_cast<std::ptrdiff_t>(budget), lines.end(),
                         [&](const Segment& x, const Segment& y) {
                             return projected_length(x, view_dir) > projected_length(y, view_dir);
                         });
        lines.resize(budget);
    }
    return lines;
}

}  // namespace sombra
