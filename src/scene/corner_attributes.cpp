#include "scene/corner_attributes.h"

#include <cmath>
#include <optional>
#include <utility>

namespace sombra {

namespace {

static_assert(kNoNormal == kNoUv && kNoUv == kNoTangent && kNoTangent == kNoColor);
constexpr std::uint32_t kNone = kNoNormal;
constexpr Index3 kNoCorners{kNone, kNone, kNone};

// Appends one attribute (values and per-corner indices) of a mesh of
// `in_triangles` triangles; `place` maps a value to world space, or to
// nothing when it becomes unusable there.
template <class T, class Place>
void append_attribute(std::vector<T>& out_values, std::vector<Index3>& out_indices, const std::vector<T>& in_values,
                      const std::vector<Index3>& in_indices, std::size_t in_triangles, std::size_t triangles_before,
                      bool mirrored, Place place) {
    const bool in_has = !in_indices.empty() && in_indices.size() == in_triangles;
    if (!in_has && out_indices.empty()) return;
    if (out_indices.empty()) out_indices.assign(triangles_before, kNoCorners);
    if (!in_has) {
        out_indices.insert(out_indices.end(), in_triangles, kNoCorners);
        return;
    }
    const auto base = static_cast<std::uint32_t>(out_values.size());
    std::vector<bool> usable(in_values.size());
    for (std::size_t i = 0; i < in_values.size(); ++i) {
        const std::optional<T> placed = place(in_values[i]);
        usable[i] = placed.has_value();
        out_values.push_back(placed ? *placed : T{});
    }
    for (const Index3& corners : in_indices) {
        Index3 mapped;
        for (int c = 0; c < 3; ++c)
            mapped[c] = corners[c] < usable.size() && usable[corners[c]] ? base + corners[c] : kNone;
        if (mirrored) std::swap(mapped[1], mapped[2]);
        out_indices.push_back(mapped);
    }
}

// v scaled to unit length, or nothing when it vanished or overflowed.
std::optional<Vec3> unit(Vec3 v) {
    const float len = length(v);
    if (!(len > 0) || !std::isfinite(len)) return std::nullopt;
    return v / len;
}

// A bit a triangle: set when none of its corner indices is kNone.
std::vector<std::uint64_t> complete_corner_bits(const std::vector<Index3>& indices) {
    std::vector<std::uint64_t> bits((indices.size() + 63) / 64, 0);
    for (std::size_t t = 0; t < indices.size(); ++t) {
        const Index3& c = indices[t];
        if (c[0] != kNone && c[1] != kNone && c[2] != kNone) bits[t / 64] |= std::uint64_t{1} << (t % 64);
    }
    return bits;
}

}  // namespace

void append_corner_attributes(TriangleMesh& out, const TriangleMesh& in, const Transform& transform) {
    const std::size_t count = in.triangles.size();
    const std::size_t before = out.triangles.size() - count;
    const bool mirrored = determinant3(transform) < 0;

    const Transform to_world = normal_transform(transform);
    append_attribute(out.normals, out.normal_indices, in.normals, in.normal_indices, count, before, mirrored,
                     [&](Vec3 n) { return unit(transform_vector(to_world, n)); });
    append_attribute(out.uvs, out.uv_indices, in.uvs, in.uv_indices, count, before, mirrored,
                     [](Vec2 uv) { return std::optional<Vec2>(uv); });
    for (std::size_t k = 0; k < in.extra_uvs.size(); ++k)
        append_attribute(out.extra_uvs[k].uvs, out.extra_uvs[k].indices, in.extra_uvs[k].uvs, in.extra_uvs[k].indices,
                         count, before, mirrored, [](Vec2 uv) { return std::optional<Vec2>(uv); });
    append_attribute(out.tangents, out.tangent_indices, in.tangents, in.tangent_indices, count, before, mirrored,
                     [&](const VertexTangent& t) -> std::optional<VertexTangent> {
                         const std::optional<Vec3> direction = unit(transform_vector(transform, t.direction));
                         if (!direction) return std::nullopt;
                         return VertexTangent{*direction, mirrored ? -t.handedness : t.handedness};
                     });
    append_attribute(out.colors, out.color_indices, in.colors, in.color_indices, count, before, mirrored,
                     [](const Rgba& c) { return std::optional<Rgba>(c); });
}

void append_corner_attributes(TriangleMesh& out, const TriangleMesh& in) {
    const std::size_t count = in.triangles.size();
    const std::size_t before = out.triangles.size() - count;
    const auto as_is = [](const auto& value) { return std::optional(value); };
    append_attribute(out.normals, out.normal_indices, in.normals, in.normal_indices, count, before, false, as_is);
    append_attribute(out.uvs, out.uv_indices, in.uvs, in.uv_indices, count, before, false, as_is);
    for (std::size_t k = 0; k < in.extra_uvs.size(); ++k)
        append_attribute(out.extra_uvs[k].uvs, out.extra_uvs[k].indices, in.extra_uvs[k].uvs, in.extra_uvs[k].indices,
                         count, before, false, as_is);
    append_attribute(out.tangents, out.tangent_indices, in.tangents, in.tangent_indices, count, before, false, as_is);
    append_attribute(out.colors, out.color_indices, in.colors, in.color_indices, count, before, false, as_is);
}

void mark_complete_corners(TriangleMesh& mesh) {
    mesh.complete_normals = complete_corner_bits(mesh.normal_indices);
    mesh.complete_uvs = complete_corner_bits(mesh.uv_indices);
}

}  // namespace sombra
