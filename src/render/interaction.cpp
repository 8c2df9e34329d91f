#include "render/interaction.h"

#include <cmath>

namespace sombra {

SurfaceInteraction make_surface_interaction(const TriangleMesh& mesh, const Ray& ray, const Hit& hit) {
    const auto [p0, p1, p2] = hit.has_corners ? hit.corners : triangle_corners(mesh, hit.triangle);
    const float b0 = 1.0f - hit.b1 - hit.b2;

    SurfaceInteraction si;
    // Rebuilding x from the barycentrics keeps it on the triangle's plane to
    // within a few ulps of the vertex coordinates, whatever the distance
    // travelled; o + t·d would carry t's error along the ray.
    const Vec3 w0 = b0 * p0, w1 = hit.b1 * p1, w2 = hit.b2 * p2;
    si.position = w0 + w1 + w2;
    // A generous multiple (2^-19 ≈ 16 ulps) of the rounding error of that sum.
    si.position_error = (abs(w0) + abs(w1) + abs(w2)) * 0x1p-19f;

    Vec3 n_g = normalize(cross(p1 - p0, p2 - p0));
    // Two-sided surfaces: the geometric normal faces the ray's origin; the
    // winding normal's side is remembered for glass and one-sided emitters.
    si.outside = dot(n_g, ray.dir) <= 0.0f;
    if (!si.outside) n_g = -n_g;
    si.n_g = n_g;
    si.n_s = n_g;

    if (has_vertex_normals(mesh, hit.triangle)) {
        const Index3& ni = mesh.normal_indices[hit.triangle];
        const Vec3 blended = b0 * mesh.normals[ni[0]] + hit.b1 * mesh.normals[ni[1]] + hit.b2 * mesh.normals[ni[2]];
        const float len = length(blended);
        // Opposing corner normals can cancel: fall back to the geometric normal.
        if (len > 1e-12f && std::isfinite(len)) {
            Vec3 n_s = blended / len;
            if (dot(n_s, n_g) < 0.0f) n_s = -n_s;
            si.n_s = n_s;
        }
    }
    si.has_uv = interpolate_uv(mesh, hit.triangle, hit.b1, hit.b2, si.uv);
    si.b1 = hit.b1;
    si.b2 = hit.b2;
    si.triangle = hit.triangle;
    si.material = mesh.material_ids[hit.triangle];
    return si;
}

}  // namespace sombra
