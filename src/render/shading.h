// Textured materials at a hit (spec §12): the material's textured parameters
// looked up at the hit's uv into a plain Material that the BSDFs use as they
// use any other, and normal or bump maps applied to the shading normal.
// Untextured materials cost one branch: they are returned as they are.
#pragma once

#include <cstdint>

#include "core/vec3.h"
#include "render/interaction.h"
#include "scene/scene.h"

namespace sombra {

// The material at `si` as the BSDFs see it. Untextured, and not a pbr
// material on a triangle with vertex colours: scene.materials[si.material]
// itself, `si` and `scratch` untouched. Otherwise `scratch`, holding the
// material's parameters with a pbr base colour times the interpolated
// vertex colour's RGB (glTF COLOR_0; its alpha is the cut-outs'), then each
// textured parameter times its texel at si.uv (reflectances clamped to
// [0, 1], ke to >= 0); and on faces with uvs (si.has_uv) a normal map (in
// the vertex tangents' frame where the triangle has them, else its uv
// parameterisation's), else a bump map, replaces si.n_s, kept within n_g's
// hemisphere. A coated pbr material (KHR_materials_clearcoat) gets its
// coat's normal in si.n_c where it differs from the final si.n_s: its
// clearcoat_normal_map's, resolved as the normal map is, else si.n_s as it
// was before the base's maps. The result lives as long as `scratch` (or the scene).
// `surface_footprint` is the ray cone's footprint on the surface, world
// units (render/ray_cone.h): when > 0 on a textured face with uvs, every
// lookup is filtered at that footprint (eval_texture_ref_filtered) and
// si.uv_footprint says how wide it was in uv. 0: full resolution, as spec
// §12's default.
const Material& resolve_material(const Scene& scene, SurfaceInteraction& si, Material& scratch,
                                 float surface_footprint = 0.0f);

// True when resolve_material would fill `scratch` for `si`: a textured
// material, or a pbr one on a triangle with vertex colours. False: it would
// return scene.materials[si.material] itself, so a caller may use that
// without constructing a scratch Material (about 500 bytes to initialise;
// the direct integrator would do it once per camera ray).
inline bool needs_resolved_material(const Scene& scene, const SurfaceInteraction& si) {
    const Material& m = scene.materials[si.material];
    return m.textured ||
           (m.type == MaterialType::Pbr && has_vertex_colors(surface_mesh(scene, si.instance), si.triangle));
}

// The radiance `material` emits at world point y of `triangle` of
// surface_mesh(scene, instance) (towards a side where it emits): ke, times
// ke's texture at y's uv when it has one. For light sampling, where y is a
// sampled point rather than a hit.
Vec3 emission_at(const Scene& scene, const Material& material, std::uint32_t triangle, Vec3 y,
                 std::uint32_t instance = kNoInstance);

// The shading normal that a tangent-space normal-map value `n_map` (unit,
// +z along the surface normal) gives at a point whose surface normal is n
// (unit) and whose position changes by dpdu, dpdv per unit of u and v
// (OpenGL convention: +x along dpdu, +y along dpdv, Gram–Schmidt
// orthonormalised against n). Returns n when the uvs are degenerate there.
// A vertex tangent t with its handedness w gives the frame as
// dpdu = t, dpdv = w·(n × t).
Vec3 apply_normal_map(Vec3 n, Vec3 dpdu, Vec3 dpdv, Vec3 n_map);

// The shading normal of a bump map (pbrt's): the surface displaced by height
// h along n, with dh/du = dhdu and dh/dv = dhdv, has the normal
// (dpdu + dhdu·n) × (dpdv + dhdv·n), turned to n's side. n when degenerate.
Vec3 apply_bump(Vec3 n, Vec3 dpdu, Vec3 dpdv, float dhdu, float dhdv);

}  // namespace sombra
