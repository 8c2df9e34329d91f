// Polygon → triangles. The geometry is done in double, relative to corner 0,
// because OBJ polygons far from the origin (thousands of units) lose too many
// float bits for the orientation tests.
#include "io/mesh_builder.h"

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

namespace {

// Every per-corner attribute marks a missing corner with the same value.
static_assert(kNoNormal == kNoUv && kNoUv == kNoTangent && kNoTangent == kNoColor);
constexpr Index3 kNoCorners{kNoNormal, kNoNormal, kNoNormal};
// Marks a vertex or normal removed from the compacted arrays.
constexpr std::uint32_t kRemoved = 0xffffffffu;

// "1 face", "3 faces"; `many` for irregular plurals.
std::string plural(std::size_t count, const std::string& one, const std::string& many = "") {
    return std::to_string(count) + " " + (count == 1 ? one : (many.empty() ? one + "s" : many));
}

// The corners of one optional per-corner attribute (normals, uvs, tangents,
// colours) for a face of n corners: `corners`, or empty when it does not
// give one per corner. The first face that has the attribute starts its
// index array, the earlier triangles without.
std::span<const std::uint32_t> start_corners(std::span<const std::uint32_t> corners, std::size_t n, bool& present,
                                             std::vector<Index3>& indices, std::size_t triangles_before) {
    if (corners.size() != n) return {};
    if (!present) {
        indices.assign(triangles_before, kNoCorners);
        present = true;
    }
    return corners;
}

void push_corners(std::vector<Index3>& indices, bool present, std::span<const std::uint32_t> corners, std::uint32_t a,
                  std::uint32_t b, std::uint32_t c) {
    if (present) indices.push_back(corners.empty() ? kNoCorners : Index3{corners[a], corners[b], corners[c]});
}

// Scales the direction (direction_of(value)) of every value to unit length
// and removes those of zero length or not finite, their corners then
// without; the attribute goes when no corner keeps one. Returns how many
// were removed.
template <class T, class DirectionOf>
std::size_t keep_unit_directions(std::vector<T>& values, std::vector<Index3>& indices, DirectionOf direction_of) {
    std::vector<std::uint32_t> remap(values.size(), kRemoved);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const Vec3 d = direction_of(values[i]);
        // In double, so that tiny but valid directions do not underflow.
        const double len = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
        if (!(len > 0) || !std::isfinite(len)) continue;
        values[kept] = values[i];
        direction_of(values[kept]) = Vec3{float(d.x / len), float(d.y / len), float(d.z / len)};
        remap[i] = static_cast<std::uint32_t>(kept++);
    }
    const std::size_t removed = values.size() - kept;
    values.resize(kept);

    bool any_corner = false;
    for (Index3& corners : indices) {
        for (std::uint32_t& c : corners) {
            if (c != kNoCorners[0]) c = c < remap.size() ? remap[c] : kNoCorners[0];
            any_corner |= c != kNoCorners[0];
        }
    }
    if (!any_corner) {
        values.clear();
        indices.clear();
    }
    return removed;
}

}  // namespace

void MeshBuilder::reserve_triangles(std::size_t count) {
    mesh_.triangles.reserve(count);
    mesh_.material_ids.reserve(count);
}

void MeshBuilder::add_face(std::span<const std::uint32_t> position_corners,
                           std::span<const std::uint32_t> normal_corners, std::uint32_t material,
                           std::span<const std::uint32_t> uv_corners, std::span<const std::uint32_t> tangent_corners,
                           std::span<const std::uint32_t> color_corners, const ExtraUvCorners& extra_uv_corners) {
    const std::size_t n = position_corners.size();
    if (n < 3) {
        ++skipped_small_faces;
        return;
    }
    const std::size_t before = mesh_.triangles.size();
    normal_corners = start_corners(normal_corners, n, has_normals_, mesh_.normal_indices, before);
    uv_corners = start_corners(uv_corners, n, has_uvs_, mesh_.uv_indices, before);
    tangent_corners = start_corners(tangent_corners, n, has_tangents_, mesh_.tangent_indices, before);
    color_corners = start_corners(color_corners, n, has_colors_, mesh_.color_indices, before);
    ExtraUvCorners extra = extra_uv_corners;
    for (std::size_t k = 0; k < extra.size(); ++k)
        extra[k] = start_corners(extra[k], n, has_extra_uvs_[k], mesh_.extra_uvs[k].indices, before);
    auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        mesh_.triangles.push_back({position_corners[a], position_corners[b], position_corners[c]});
        push_corners(mesh_.normal_indices, has_normals_, normal_corners, a, b, c);
        push_corners(mesh_.uv_indices, has_uvs_, uv_corners, a, b, c);
        push_corners(mesh_.tangent_indices, has_tangents_, tangent_corners, a, b, c);
        push_corners(mesh_.color_indices, has_colors_, color_corners, a, b, c);
        for (std::size_t k = 0; k < extra.size(); ++k)
            push_corners(mesh_.extra_uvs[k].indices, has_extra_uvs_[k], extra[k], a, b, c);
        mesh_.material_ids.push_back(material);
    };
    if (n == 3) {
        emit(0, 1, 2);
        return;
    }
    corner_positions_.clear();
    for (std::uint32_t index : position_corners) corner_positions_.push_back(positions[index]);
    split_.clear();
    if (triangulate_polygon(corner_positions_, scratch_, split_) == PolygonSplit::OverlapFan) ++overlap_fans_;
    for (const PolygonTriangle& t : split_) emit(t[0], t[1], t[2]);
}

void MeshBuilder::clean_directions(Diagnostics& diag) {
    if (!has_normals_) mesh_.normals.clear();
    if (!has_tangents_) mesh_.tangents.clear();
    const std::size_t bad_normals =
        keep_unit_directions(mesh_.normals, mesh_.normal_indices, [](Vec3& n) -> Vec3& { return n; });
    const std::size_t bad_tangents = keep_unit_directions(mesh_.tangents, mesh_.tangent_indices,
                                                          [](VertexTangent& t) -> Vec3& { return t.direction; });
    if (bad_normals > 0) diag.warn(where_, plural(bad_normals, "normal") + " of zero length or not finite ignored");
    if (bad_tangents > 0) diag.warn(where_, plural(bad_tangents, "tangent") + " of zero length or not finite ignored");
}

void MeshBuilder::drop_non_finite_positions(Diagnostics& diag) {
    std::vector<Vec3>& pos = mesh_.positions;
    std::size_t bad_vertices = 0;
    for (const Vec3& p : pos) bad_vertices += !is_finite(p);
    if (bad_vertices == 0) return;

    std::vector<std::uint32_t> remap(pos.size(), kRemoved);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < pos.size(); ++i) {
        if (!is_finite(pos[i])) continue;
        pos[kept] = pos[i];
        remap[i] = static_cast<std::uint32_t>(kept++);
    }
    pos.resize(kept);

    // The per-corner attributes that are present follow their triangles.
    std::vector<std::vector<Index3>*> per_corner;
    for (std::vector<Index3>* indices :
         {&mesh_.normal_indices, &mesh_.uv_indices, &mesh_.tangent_indices, &mesh_.color_indices})
        if (!indices->empty()) per_corner.push_back(indices);
    for (UvSet& set : mesh_.extra_uvs)
        if (!set.indices.empty()) per_corner.push_back(&set.indices);
    std::size_t out = 0;
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
        const Index3& tri = mesh_.triangles[t];
        const Index3 mapped{remap[tri[0]], remap[tri[1]], remap[tri[2]]};
        if (mapped[0] == kRemoved || mapped[1] == kRemoved || mapped[2] == kRemoved) continue;
        mesh_.triangles[out] = mapped;
        for (std::vector<Index3>* indices : per_corner) (*indices)[out] = (*indices)[t];
        mesh_.material_ids[out] = mesh_.material_ids[t];
        ++out;
    }
    const std::size_t dropped = mesh_.triangles.size() - out;
    mesh_.triangles.resize(out);
    for (std::vector<Index3>* indices : per_corner) indices->resize(out);
    mesh_.material_ids.resize(out);
    diag.warn(where_, "dropped " + plural(dropped, "triangle") + " touching " +
                          plural(bad_vertices, "vertex", "vertices") + " with non-finite (nan/inf) coordinates");
}

LoadedMesh MeshBuilder::finish(std::vector<Material> materials, Diagnostics& diag) {
    bool needs_default = false;
    LoadedMesh out;
    out.mesh = finish_mesh(materials.size(), needs_default, diag);
    if (needs_default) materials.push_back(default_material());
    out.materials = std::move(materials);
    return out;
}

TriangleMesh MeshBuilder::finish_mesh(std::size_t material_count, bool& uses_default, Diagnostics& diag) {
    if (skipped_small_faces > 0) {
        diag.warn(where_, "skipped " + plural(skipped_small_faces, "face") + " with fewer than 3 corners");
    }
    if (overlap_fans_ > 0) {
        diag.warn(where_, plural(overlap_fans_, "polygon") + " with more than " + std::to_string(kMaxEarClipCorners) +
                              " corners overlap themselves: split as a fan anyway");
    }
    const std::size_t vertex_count = positions.size();
    mesh_.positions = std::move(positions);
    mesh_.normals = std::move(normals);
    mesh_.uvs = std::move(uvs);
    if (!has_uvs_) mesh_.uvs.clear();
    for (std::size_t k = 0; k < extra_uvs.size(); ++k) {
        mesh_.extra_uvs[k].uvs = std::move(extra_uvs[k]);
        if (!has_extra_uvs_[k]) mesh_.extra_uvs[k].uvs.clear();
    }
    mesh_.tangents = std::move(tangents);
    mesh_.colors = std::move(colors);
    if (!has_colors_) mesh_.colors.clear();
    const bool had_triangles = !mesh_.triangles.empty();
    clean_directions(diag);
    drop_non_finite_positions(diag);
    if (mesh_.triangles.empty()) {
        throw Error(where_, had_triangles ? "no triangles left: every triangle touches a non-finite vertex"
                                          : "no triangles (" + plural(vertex_count, "vertex", "vertices") +
                                                ", no face with 3 or more corners)");
    }

    const auto default_id = static_cast<std::uint32_t>(material_count);
    for (std::uint32_t& id : mesh_.material_ids) {
        if (id >= default_id) {
            id = default_id;
            uses_default = true;
        }
    }
    return std::move(mesh_);
}

}  // namespace sombra
