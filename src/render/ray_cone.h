// Ray cones: how wide a pixel's share of the world is where a ray meets a
// surface, for choosing a texture's mip level (--texture-filter mipmap; the
// method of Akenine-Möller et al., "Texture Level of Detail Strategies for
// Real-Time Ray Tracing", Ray Tracing Gems, ch. 20).
//
// A camera ray carries the cone of its pixel: width 0 at the eye, spread
// angle γ with γ² the pixel's solid angle as seen along that ray. At a hit t
// away the cone is γ·t wide across the ray, and on the surface its footprint
// is γ·t/|cos θ| along its long axis (θ between the ray and the normal: the
// footprint's ellipse stretches by 1/|cos θ| one way, and taking that axis,
// as GPUs' isotropic filtering does, blurs at grazing angles rather than
// aliasing). resolve_material (render/shading.h) turns that width into uv
// units with the triangle's uv-to-world scale, and the texture's size turns
// it into texels: λ = log2 of that (scene/texture_mipmap.h).
//
// After a hit the cone goes on only through delta scattering (mirror, glass):
// the reflected or refracted cone keeps its spread (flat surfaces; curvature
// is ignored) and starts with its width at the hit, so a mirror shows a
// filtered texture as the camera would. After any other scattering the new
// ray has no cone and every later lookup reads the full-resolution texture,
// as with the option off: a sampled bounce's direction is random, so the
// texture's detail it meets is integrated over the pixel's samples like any
// other detail of the incident light (noise that converges, not the aliasing
// of a regular pixel grid), and it keeps indirect light exactly that of the
// bilinear render. It also keeps multiple importance sampling consistent: a
// textured emitter that a non-delta bounce meets is weighted against light
// sampling, which reads its texture at full resolution (emission_at), so
// both strategies must see the same emission; filtered lookups happen only
// after the camera or delta scattering, where light sampling has no share.
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace sombra {

struct RayCone {
    float width = 0;   // across the ray at its origin, world units
    float spread = 0;  // radians: the width grows by spread per unit of distance
    // False for the empty cone: lookups at full resolution.
    bool active() const { return width > 0.0f || spread > 0.0f; }
};

// The camera's pixel as a parallelogram on its image plane: (2/W)·left ×
// (2/H)·up (render/camera.h), whose length is the pixel's area at the plane's
// distance |forward| and whose direction is the plane's normal.
inline Vec3 camera_pixel_area(Vec3 left, Vec3 up, int width, int height) {
    return cross(left, up) * (4.0f / (static_cast<float>(width) * static_cast<float>(height)));
}

// The cone of the camera ray along `dir` (from camera_ray, not unit: origin
// to the image plane): γ² = |pixel_area · dir| / |dir|³, the pixel's solid
// angle seen along dir, so that off-axis pixels, which look smaller, get
// narrower cones.
// An orthographic camera's rays are parallel: each cone keeps the pixel's
// width (the square root of its area) and never spreads.
inline RayCone camera_ray_cone(Vec3 pixel_area, Vec3 dir, bool orthographic) {
    if (orthographic) return RayCone{std::sqrt(length(pixel_area)), 0.0f};
    const float len = length(dir);
    return RayCone{0.0f, std::sqrt(std::fabs(dot(pixel_area, dir)) / (len * len * len))};
}

// The cone's width across the ray `distance` from its origin.
inline float cone_width(const RayCone& cone, float distance) { return cone.width + cone.spread * distance; }

// The footprint's long axis on a surface with normal n (unit) that the ray
// along `dir` (any length) meets `distance` away: cone_width / |cos θ|.
// 0 for the empty cone; +∞ when the ray grazes the surface.
inline float surface_footprint(const RayCone& cone, float distance, Vec3 dir, Vec3 n) {
    if (!cone.active()) return 0.0f;
    const float cos_theta = std::fabs(dot(n, dir)) / length(dir);
    return cone_width(cone, distance) / cos_theta;
}

// The cone of the ray leaving a hit `distance` along `cone`'s ray, after
// scattering that was delta (mirror, glass) or not: see above.
inline RayCone scattered_cone(const RayCone& cone, float distance, bool delta) {
    if (!delta || !cone.active()) return RayCone{};
    return RayCone{cone_width(cone, distance), cone.spread};
}

}  // namespace sombra
