#include "render/interaction.h"

#include <cmath>

namespace sombra {

namespace {

// The interaction at barycentrics (b1, b2) of a triangle with world corners
// p0, p1, p2, whose winding normal is (p1 − p0) × (p2 − p0) times
// `winding` (±1), and whose corners' world normals `normal(k)` gives when
// `smooth`.
template <class CornerNormal>
SurfaceInteraction make_interaction(const Vec3& p0, const Vec3& p1, const Vec3& p2, float winding, float b1, float b2,
                                    const Ray& ray, bool smooth, CornerNormal normal) {
    const float b0 = 1.0f - b1 - b2;

    SurfaceInteraction si;
    // Rebuilding x from the barycentrics keeps it on the triangle's plane to
    // within a few ulps of the vertex coordinates, whatever the distance
    // travelled; o + t·d would carry t's error along the ray.
    const Vec3 w0 = b0 * p0, w1 = b1 * p1, w2 = b2 * p2;
    si.position = w0 + w1 + w2;
    // A generous multiple (2^-19 ≈ 16 ulps) of the rounding error of that sum.
    si.position_error = (abs(w0) + abs(w1) + abs(w2)) * 0x1p-19f;

    Vec3 n_g = winding * normalize(cross(p1 - p0, p2 - p0));
    // Two-sided surfaces: the geometric normal faces the ray's origin; the
    // winding normal's side is remembered for glass and one-sided emitters.
    si.outside = dot(n_g, ray.dir) <= 0.0f;
    if (!si.outside) n_g = -n_g;
    si.n_g = n_g;
    si.n_s = n_g;

    if (smooth) {
        const Vec3 blended = b0 * normal(0) + b1 * normal(1) + b2 * normal(2);
        const float len = length(blended);
        // Opposing corner normals can cancel: fall back to the geometric normal.
        if (len > 1e-12f && std::isfinite(len)) {
            Vec3 n_s = blended / len;
            if (dot(n_s, n_g) < 0.0f) n_s = -n_s;
            si.n_s = n_s;
        }
    }
    return si;
}

// The hit's attributes that do not depend on placement.
void set_attributes(SurfaceInteraction& si, const TriangleMesh& mesh, const Hit& hit) {
    si.has_uv = interpolate_uv(mesh, hit.triangle, hit.b1, hit.b2, si.uv);
    si.b1 = hit.b1;
    si.b2 = hit.b2;
    si.triangle = hit.triangle;
    si.instance = hit.instance;
    si.material = mesh.material_ids[hit.triangle];
}

// The world direction of a normal in an instance's coordinates, as
// append_corner_attributes places a flattened copy's (the geometric normal
// if it vanishes).
Vec3 normal_to_world(const Instance& instance, Vec3 n) {
    const Vec3 w = transform_vector(instance.normal_to_world, n);
    const float len = length(w);
    return len > 0.0f && std::isfinite(len) ? w / len : Vec3{0.0f};
}

}  // namespace

std::array<Vec3, 3> instanced_triangle_corners(const Scene& scene, std::uint32_t triangle, std::uint32_t instance) {
    const Instance& in = scene.instances[instance];
    const auto [q0, q1, q2] = triangle_corners(scene.instanced_meshes[in.mesh], triangle);
    const Transform& m = in.object_to_world;
    const Vec3 p0 = transform_point(m, q0), p1 = transform_point(m, q1), p2 = transform_point(m, q2);
    if (in.mirrored) return {p0, p2, p1};
    return {p0, p1, p2};
}

SurfaceInteraction make_surface_interaction(const TriangleMesh& mesh, const Ray& ray, const Hit& hit) {
    const auto [p0, p1, p2] = hit.has_corners ? hit.corners : triangle_corners(mesh, hit.triangle);
    const bool smooth = has_vertex_normals(mesh, hit.triangle);
    const Index3* ni = smooth ? &mesh.normal_indices[hit.triangle] : nullptr;
    SurfaceInteraction si =
        make_interaction(p0, p1, p2, 1.0f, hit.b1, hit.b2, ray, smooth, [&](int k) { return mesh.normals[(*ni)[k]]; });
    set_attributes(si, mesh, hit);
    return si;
}

SurfaceInteraction make_surface_interaction(const Scene& scene, const Ray& ray, const Hit& hit) {
    if (hit.instance == kNoInstance) return make_surface_interaction(scene.geometry, ray, hit);
    const Instance& instance = scene.instances[hit.instance];
    const TriangleMesh& mesh = scene.instanced_meshes[instance.mesh];
    const auto [q0, q1, q2] = hit.has_corners ? hit.corners : triangle_corners(mesh, hit.triangle);
    const Transform& m = instance.object_to_world;
    const Vec3 p0 = transform_point(m, q0), p1 = transform_point(m, q1), p2 = transform_point(m, q2);
    const bool smooth = has_vertex_normals(mesh, hit.triangle);
    const Index3* ni = smooth ? &mesh.normal_indices[hit.triangle] : nullptr;
    // A mirroring instance reverses the corners' turn; its winding normal
    // keeps the side the mesh gave it (spec §11, §23).
    SurfaceInteraction si = make_interaction(p0, p1, p2, instance.mirrored ? -1.0f : 1.0f, hit.b1, hit.b2, ray, smooth,
                                             [&](int k) { return normal_to_world(instance, mesh.normals[(*ni)[k]]); });
    // The ray met the mesh in its own coordinates: a ray leaving this point
    // is carried back there, which rounds its origin once more.
    si.position_error = si.position_error + (abs(si.position) + abs(Vec3{m.m[3], m.m[7], m.m[11]})) * 0x1p-20f;
    set_attributes(si, mesh, hit);
    return si;
}

}  // namespace sombra
