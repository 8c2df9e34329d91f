#include "render/integrator.h"

#include <cmath>

#include "render/brdf.h"

namespace sombra {

namespace {

// What the integrator needs to know about a hit point.
struct SurfacePoint {
    Vec3 position;
    Vec3 position_error;  // per-axis bound on |position − exact point|
    Vec3 n_g;             // unit geometric normal, facing the ray's origin
    Vec3 n_s;             // unit shading normal, same hemisphere as n_g
    std::uint32_t material;
};

SurfacePoint make_surface_point(const TriangleMesh& mesh, const Ray& ray, const Hit& hit) {
    const Index3& tri = mesh.triangles[hit.triangle];
    const Vec3 p0 = mesh.positions[tri[0]];
    const Vec3 p1 = mesh.positions[tri[1]];
    const Vec3 p2 = mesh.positions[tri[2]];
    const float b0 = 1.0f - hit.b1 - hit.b2;

    SurfacePoint sp;
    // Rebuilding x from the barycentrics keeps it on the triangle's plane to
    // within a few ulps of the vertex coordinates, whatever the distance
    // travelled; o + t·d would carry t's error along the ray.
    const Vec3 w0 = b0 * p0, w1 = hit.b1 * p1, w2 = hit.b2 * p2;
    sp.position = w0 + w1 + w2;
    // A generous multiple (2^-19 ≈ 16 ulps) of the rounding error of that sum.
    sp.position_error = (abs(w0) + abs(w1) + abs(w2)) * 0x1p-19f;

    Vec3 n_g = normalize(cross(p1 - p0, p2 - p0));
    // Two-sided surfaces: the geometric normal faces the ray's origin.
    if (dot(n_g, ray.dir) > 0.0f) n_g = -n_g;
    sp.n_g = n_g;
    sp.n_s = n_g;

    if (mesh.has_normals()) {
        const Index3& ni = mesh.normal_indices[hit.triangle];
        if (ni[0] != kNoNormal && ni[1] != kNoNormal && ni[2] != kNoNormal) {
            const Vec3 blended = b0 * mesh.normals[ni[0]] + hit.b1 * mesh.normals[ni[1]] + hit.b2 * mesh.normals[ni[2]];
            const float len = length(blended);
            // Opposing corner normals can cancel: fall back to the geometric normal.
            if (len > 1e-12f && std::isfinite(len)) {
                Vec3 n_s = blended / len;
                if (dot(n_s, n_g) < 0.0f) n_s = -n_s;
                sp.n_s = n_s;
            }
        }
    }
    sp.material = mesh.material_ids[hit.triangle];
    return sp;
}

}  // namespace

Vec3 trace_direct(const Scene& scene, const Accel& accel, const Ray& ray, RayCounters& counters) {
    ++counters.camera_rays;
    Hit hit;
    if (!intersect(accel, ray, hit)) return scene.background;

    const SurfacePoint sp = make_surface_point(scene.geometry, ray, hit);
    const Material& material = scene.materials[sp.material];
    const Vec3 wo = -normalize(ray.dir);
    const Vec3 shadow_origin = offset_ray_origin(sp.position, sp.position_error, sp.n_g);

    // Emission is two-sided and seen only directly (spec §4, §9).
    Vec3 radiance = material.ke;
    for (const PointLight& light : scene.lights) {
        const Vec3 to_light = light.position - sp.position;
        const float distance_squared = dot(to_light, to_light);
        if (!(distance_squared > 0.0f)) continue;  // a light exactly on the surface lights nothing
        const Vec3 wi = to_light / std::sqrt(distance_squared);
        // A light behind the surface (as seen from the camera's side) adds nothing.
        if (dot(sp.n_g, wi) <= 0.0f) continue;

        // Shadow ray: from the offset origin to the light; t = 1 reaches the
        // light, and the bound just short of it keeps the light's own
        // position (possibly on a surface) from counting as an occluder.
        ++counters.shadow_rays;
        const Ray shadow{shadow_origin, light.position - shadow_origin, 1.0f - 1e-5f};
        if (occluded(accel, shadow)) continue;

        // L += I / |c − x|² · f_r(x, ω_i, ω_o) · |n_s · ω_i|
        const Vec3 f_r = eval_brdf(material, sp.n_s, wi, wo);
        radiance += light.intensity * (std::fabs(dot(sp.n_s, wi)) / distance_squared) * f_r;
    }

    if (!is_finite(radiance)) {
        ++counters.nonfinite_samples;
        return Vec3{0.0f};
    }
    return radiance;
}

}  // namespace sombra
