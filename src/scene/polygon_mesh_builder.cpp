#include "scene/polygon_mesh_builder.h"

#include <cmath>

namespace sombra {
namespace {

constexpr Index3 kNoNormals{kNoNormal, kNoNormal, kNoNormal};
// Marks a vertex or normal removed from the compacted arrays.
constexpr std::uint32_t kRemoved = 0xffffffffu;

// "1 face", "3 faces"; `many` for irregular plurals.
std::string plural(std::size_t count, const std::string& one, const std::string& many = "") {
    return std::to_string(count) + " " + (count == 1 ? one : (many.empty() ? one + "s" : many));
}

}  // namespace

void PolygonMeshBuilder::reserve_triangles(std::size_t count) {
    mesh_.triangles.reserve(count);
    mesh_.material_ids.reserve(count);
}

void PolygonMeshBuilder::add_face(std::span<const std::uint32_t> position_corners,
                                  std::span<const std::uint32_t> normal_corners, std::uint32_t material) {
    const std::size_t n = position_corners.size();
    if (n < 3) {
        ++skipped_small_faces;
        return;
    }
    if (normal_corners.size() != n) normal_corners = {};
    if (!normal_corners.empty() && !has_normals_) {
        // First face with normals: the earlier triangles had none.
        mesh_.normal_indices.assign(mesh_.triangles.size(), kNoNormals);
        has_normals_ = true;
    }
    auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        mesh_.triangles.push_back({position_corners[a], position_corners[b], position_corners[c]});
        if (has_normals_) {
            mesh_.normal_indices.push_back(
                normal_corners.empty() ? kNoNormals : Index3{normal_corners[a], normal_corners[b], normal_corners[c]});
        }
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

void PolygonMeshBuilder::clean_normals(Diagnostics& diag) {
    if (!has_normals_) {
        mesh_.normals.clear();
        return;
    }
    std::vector<Vec3>& normals_out = mesh_.normals;
    std::vector<std::uint32_t> remap(normals_out.size(), kRemoved);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < normals_out.size(); ++i) {
        const Vec3 n = normals_out[i];
        // In double, so that tiny but valid normals do not underflow.
        const double len = std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z);
        if (!(len > 0) || !std::isfinite(len)) continue;
        const Vec3 unit{float(n.x / len), float(n.y / len), float(n.z / len)};
        normals_out[kept] = unit;
        remap[i] = static_cast<std::uint32_t>(kept++);
    }
    const std::size_t bad = normals_out.size() - kept;
    normals_out.resize(kept);

    bool any_normal = false;
    for (Index3& corners : mesh_.normal_indices) {
        for (std::uint32_t& c : corners) {
            if (c != kNoNormal) c = c < remap.size() ? remap[c] : kNoNormal;
            any_normal |= c != kNoNormal;
        }
    }
    if (!any_normal) {
        mesh_.normals.clear();
        mesh_.normal_indices.clear();
    }
    if (bad > 0) diag.warn(where_, plural(bad, "normal") + " of zero length or not finite ignored");
}

void PolygonMeshBuilder::drop_non_finite_positions(Diagnostics& diag) {
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

    const bool with_normals = mesh_.has_normals();
    std::size_t out = 0;
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
        const Index3& tri = mesh_.triangles[t];
        const Index3 mapped{remap[tri[0]], remap[tri[1]], remap[tri[2]]};
        if (mapped[0] == kRemoved || mapped[1] == kRemoved || mapped[2] == kRemoved) continue;
        mesh_.triangles[out] = mapped;
        if (with_normals) mesh_.normal_indices[out] = mesh_.normal_indices[t];
        mesh_.material_ids[out] = mesh_.material_ids[t];
        ++out;
    }
    const std::size_t dropped = mesh_.triangles.size() - out;
    mesh_.triangles.resize(out);
    if (with_normals) mesh_.normal_indices.resize(out);
    mesh_.material_ids.resize(out);
    diag.warn(where_, "dropped " + plural(dropped, "triangle") + " touching " +
                          plural(bad_vertices, "vertex", "vertices") + " with non-finite (nan/inf) coordinates");
}

LoadedMesh PolygonMeshBuilder::finish(std::vector<Material> materials, Diagnostics& diag) {
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
    const bool had_triangles = !mesh_.triangles.empty();
    clean_normals(diag);
    drop_non_finite_positions(diag);
    if (mesh_.triangles.empty()) {
        throw Error(where_, had_triangles ? "no triangles left: every triangle touches a non-finite vertex"
                                          : "no triangles (" + plural(vertex_count, "vertex", "vertices") +
                                                ", no face with 3 or more corners)");
    }

    const auto default_id = static_cast<std::uint32_t>(materials.size());
    bool needs_default = false;
    for (std::uint32_t& id : mesh_.material_ids) {
        if (id >= default_id) {
            id = default_id;
            needs_default = true;
        }
    }
    if (needs_default) materials.push_back(default_material());
    return LoadedMesh{std::move(mesh_), std::move(materials)};
}

}  // namespace sombra
