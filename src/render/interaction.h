// What the integrators know about a point where a ray met a surface: both
// normals, the side the ray came from, and a bound on the point's rounding
// error for spawning rays that cannot re-hit the surface they leave.
#pragma once

#include <array>
#include <cstdint>

#include "accel/accel.h"
#include "core/ray.h"
#include "scene/mesh.h"

namespace sombra {

struct SurfaceInteraction {
    Vec3 position;
    Vec3 position_error;  // per-axis bound on |position − exact point|
    Vec3 n_g;             // unit geometric normal, facing the ray's origin (surfaces are two-sided)
    Vec3 n_s;             // unit shading normal (blended vertex normals, else n_g), same hemisphere as n_g
    // KHR_materials_clearcoat's coat normal where it differs from n_s (set
    // by resolve_material, render/shading.h: the coat's own normal map, or
    // n_s as it was before the base's normal or bump map); zero: the coat
    // shares n_s, as every material without a coat.
    Vec3 n_c;
    // True when the ray arrived from the side the triangle's winding normal
    // n_w = (p1 − p0) × (p2 − p0) points to: into a dielectric's medium, and
    // the side a quad light emits toward (spec §10, §11).
    bool outside = true;
    // Texture coordinates blended with the barycentric weights when all three
    // corners have one (has_uv), else (0, 0) (spec §12).
    Vec2 uv;
    bool has_uv = false;
    // Under mip-mapping, the width in uv of the ray cone's footprint that
    // textures were filtered over at this hit (render/shading.h); 0: read at
    // full resolution.
    float uv_footprint = 0;
    // The hit's barycentric weights of corners 1 and 2 (corner 0 weighs
    // 1 − b1 − b2), for the vertex attributes read only while shading
    // (tangents, colours).
    float b1 = 0, b2 = 0;
    std::uint32_t triangle = 0;  // in surface_mesh(scene, instance)
    std::uint32_t instance = kNoInstance;
    std::uint32_t material = 0;
};

// The interaction for `hit` (from intersect()) of `ray` on `mesh`, the world
// geometry (hit.instance is kNoInstance).
SurfaceInteraction make_surface_interaction(const TriangleMesh& mesh, const Ray& ray, const Hit& hit);

// The interaction for any hit of `ray` in `scene`: in an instance, the hit
// triangle's corners and vertex normals are carried to world space as the
// builder carries a flattened copy's (scene/scene_builder.h), so both shade
// alike up to the rounding of the hit itself.
SurfaceInteraction make_surface_interaction(const Scene& scene, const Ray& ray, const Hit& hit);

// Directions in the instance's coordinates (a tangent, a position
// derivative) carried to world space; unchanged for kNoInstance.
inline Vec3 vector_to_world(const Scene& scene, std::uint32_t instance, Vec3 v) {
    return instance == kNoInstance ? v : transform_vector(scene.instances[instance].object_to_world, v);
}

// The world corners of `triangle` of surface_mesh(scene, instance), in an
// order whose (p1 − p0) × (p2 − p0) is its winding normal: an instance's are
// carried by object_to_world, a mirror's corners 1 and 2 swapped, exactly as
// the builder places a flattened copy's (spec §11, §23). For light sampling
// and explain, which see an emitter as its world triangle.
std::array<Vec3, 3> instanced_triangle_corners(const Scene& scene, std::uint32_t triangle, std::uint32_t instance);
inline std::array<Vec3, 3> world_triangle_corners(const Scene& scene, std::uint32_t triangle, std::uint32_t instance) {
    return instance == kNoInstance ? triangle_corners(scene.geometry, triangle)
                                   : instanced_triangle_corners(scene, triangle, instance);
}

// Where a ray leaving surface point x should start so that it cannot hit the
// surface it leaves: x moved along the geometric normal n_g (pointing to the
// side the ray leaves towards) by a bound on x's floating-point error.
inline Vec3 offset_ray_origin(Vec3 x, Vec3 error, Vec3 n_g) {
    const float d = dot(abs(n_g), error);
    return x + d * n_g;
}

// The origin of a ray leaving `si` in direction `dir`: offset to dir's side.
inline Vec3 spawn_origin(const SurfaceInteraction& si, Vec3 dir) {
    return offset_ray_origin(si.position, si.position_error, dot(si.n_g, dir) > 0.0f ? si.n_g : -si.n_g);
}

}  // namespace sombra
