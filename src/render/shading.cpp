#include "render/shading.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sombra {

namespace {

// How far above n_g's horizon a perturbed shading normal is kept (cos θ).
constexpr float kMinShadingCos = 1e-2f;

// ref's image at uv, filtered over a footprint uv_footprint wide (0: full resolution).
Rgba lookup(const Scene& scene, const TextureRef& ref, Vec2 uv, float uv_footprint) {
    return eval_texture_ref_filtered(scene.textures, ref, uv, uv_footprint);
}

// How many uv units of set `set` one world unit is on si's triangle (√ of
// its uv area over its world area), or 0 when either is degenerate or the
// triangle lacks the set.
float uv_per_world(const Scene& scene, const SurfaceInteraction& si, unsigned set) {
    const TriangleMesh& mesh = surface_mesh(scene, si.instance);
    Vec2 t[3];
    if (!uv_set_corners(mesh, set, si.triangle, t)) return 0.0f;
    const Index3& p = mesh.triangles[si.triangle];
    const Vec3 e1 = vector_to_world(scene, si.instance, mesh.positions[p[1]] - mesh.positions[p[0]]);
    const Vec3 e2 = vector_to_world(scene, si.instance, mesh.positions[p[2]] - mesh.positions[p[0]]);
    const float world = length(cross(e1, e2));
    const Vec2 t0 = t[0], t1 = t[1], t2 = t[2];
    const float uv = std::fabs((t1.x - t0.x) * (t2.y - t0.y) - (t1.y - t0.y) * (t2.x - t0.x));
    const float scale = std::sqrt(uv / world);
    return std::isfinite(scale) ? scale : 0.0f;
}

Vec3 clamp_rgb(Vec3 c, float hi) {
    return {std::clamp(c.x, 0.0f, hi), std::clamp(c.y, 0.0f, hi), std::clamp(c.z, 0.0f, hi)};
}

// The position derivatives of a triangle's uv parameterisation (set
// `set`), or false when its uvs are degenerate (zero area in uv, or
// non-finite) or missing.
bool position_derivatives(const TriangleMesh& mesh, std::uint32_t triangle, unsigned set, Vec3& dpdu, Vec3& dpdv) {
    Vec2 t[3];
    if (!uv_set_corners(mesh, set, triangle, t)) return false;
    const Index3& p = mesh.triangles[triangle];
    const Vec3 e1 = mesh.positions[p[1]] - mesh.positions[p[0]];
    const Vec3 e2 = mesh.positions[p[2]] - mesh.positions[p[0]];
    const Vec2 t0 = t[0], t1 = t[1], t2 = t[2];
    const float du1 = t1.x - t0.x, dv1 = t1.y - t0.y, du2 = t2.x - t0.x, dv2 = t2.y - t0.y;
    const float det = du1 * dv2 - dv1 * du2;
    if (!(std::fabs(det) > 1e-12f) || !std::isfinite(det)) return false;
    dpdu = (dv2 * e1 - dv1 * e2) / det;
    dpdv = (du1 * e2 - du2 * e1) / det;
    return is_finite(dpdu) && is_finite(dpdv);
}

// n moved into n_g's hemisphere, at least kMinShadingCos above its horizon.
Vec3 keep_above(Vec3 n, Vec3 n_g) {
    const float c = dot(n, n_g);
    if (c >= kMinShadingCos) return n;
    const Vec3 tangent = n - c * n_g;
    const float len = length(tangent);
    if (!(len > 1e-6f) || !std::isfinite(len)) return n_g;
    return tangent * (std::sqrt(1.0f - kMinShadingCos * kMinShadingCos) / len) + kMinShadingCos * n_g;
}

// position_derivatives at si's triangle, in world space.
bool world_position_derivatives(const Scene& scene, const SurfaceInteraction& si, unsigned set, Vec3& dpdu,
                                Vec3& dpdv) {
    if (!position_derivatives(surface_mesh(scene, si.instance), si.triangle, set, dpdu, dpdv)) return false;
    dpdu = vector_to_world(scene, si.instance, dpdu);
    dpdv = vector_to_world(scene, si.instance, dpdv);
    return true;
}

// The two directions of the tangent frame at si around the unit normal n,
// as apply_normal_map takes them: the vertex tangent t and
// handedness·(n × t) where the triangle's corners all have one (glTF
// TANGENT, spec §12) and it is not along n, else the triangle's uv
// derivatives dpdu, dpdv (of uv set `set`). False when neither exists. In an instance the
// tangent is carried to world space and a mirror flips its handedness, as
// for a flattened copy (scene/corner_attributes.h).
bool tangent_frame(const Scene& scene, const SurfaceInteraction& si, unsigned set, Vec3 n, Vec3& along_u,
                   Vec3& along_v) {
    Vec3 t;
    float handedness = 1;
    if (interpolate_tangent(surface_mesh(scene, si.instance), si.triangle, si.b1, si.b2, t, handedness)) {
        if (si.instance != kNoInstance) {
            t = vector_to_world(scene, si.instance, t);
            if (scene.instances[si.instance].mirrored) handedness = -handedness;
        }
        const float in_plane = length(t - dot(n, t) * n);
        if (in_plane > 1e-6f * length(t) && std::isfinite(in_plane)) {
            along_u = t;
            along_v = handedness * cross(n, t);
            return true;
        }
    }
    return world_position_derivatives(scene, si, set, along_u, along_v);
}

// The unit tangent-space normal a normal map's texel encodes, its x and y
// scaled by `scale` (glTF's normalTexture.scale: normalize((2·texel − 1) ⊙
// (scale, scale, 1))); false when that has no direction.
bool normal_map_value(const Rgba& texel, float scale, Vec3& n_map) {
    const Vec3 m{(2.0f * texel[0] - 1.0f) * scale, (2.0f * texel[1] - 1.0f) * scale, 2.0f * texel[2] - 1.0f};
    const float len = length(m);
    if (!(len > 1e-6f) || !std::isfinite(len)) return false;
    n_map = m / len;
    return true;
}

// The uv of `ref`'s set at si and the footprint's width there (0: full
// resolution, as under `surface_footprint` 0): si's own for set 0, else
// interpolated here; false when si's triangle lacks that set ≥ 1 (the
// texture is then not applied: glTF's texCoord naming a missing set).
bool uv_of(const Scene& scene, const SurfaceInteraction& si, const TextureRef& ref, float surface_footprint, Vec2& uv,
           float& uv_footprint) {
    if (ref.uv_set == 0) {
        uv = si.uv;
        uv_footprint = si.uv_footprint;
        return true;
    }
    if (!interpolate_uv_set(surface_mesh(scene, si.instance), ref.uv_set, si.triangle, si.b1, si.b2, uv)) return false;
    uv_footprint = surface_footprint > 0.0f ? surface_footprint * uv_per_world(scene, si, ref.uv_set) : 0.0f;
    return true;
}

// The shading normal of tangent-space normal map `map` (of scale `scale`) at
// si around si.n_s, or si.n_s where si lacks the map's uv set or a tangent
// frame: the base's normalTexture and the coat's clearcoatNormalTexture alike.
Vec3 normal_mapped(const Scene& scene, const TextureRef& map, float scale, const SurfaceInteraction& si,
                   float surface_footprint) {
    // The maps perturb the surface's front (its winding normal's side); seen
    // from the back the same sheet shows the mirror image: the result is
    // turned back to the side the ray came from.
    const Vec3 front = si.outside ? si.n_s : -si.n_s;
    Vec2 uv;
    float uv_footprint = 0;
    Vec3 along_u, along_v, n_map;
    if (!uv_of(scene, si, map, surface_footprint, uv, uv_footprint) ||
        !tangent_frame(scene, si, map.uv_set, front, along_u, along_v))
        return si.n_s;
    Vec3 n = front;
    if (normal_map_value(lookup(scene, map, uv, uv_footprint), scale, n_map))
        n = apply_normal_map(front, along_u, along_v, n_map);
    if (!si.outside) n = -n;
    return keep_above(n, si.n_g);
}

// A bump map's shading normal at si (where it has the map's uv set), or si.n_s.
Vec3 bumped_normal(const Scene& scene, const MaterialTextures& t, const SurfaceInteraction& si,
                   float surface_footprint) {
    const Vec3 front = si.outside ? si.n_s : -si.n_s;
    const TextureRef& map = t.bump_map;
    Vec2 uv;
    float uv_footprint = 0;
    Vec3 dpdu, dpdv;
    if (!uv_of(scene, si, map, surface_footprint, uv, uv_footprint) ||
        !world_position_derivatives(scene, si, map.uv_set, dpdu, dpdv))
        return si.n_s;
    const Texture& h = scene.textures[map.texture];
    // Central differences one texel apart around the hit.
    const float du = 1.0f / static_cast<float>(h.width), dv = 1.0f / static_cast<float>(h.height);
    const auto height = [&](float u, float v) { return lookup(scene, map, Vec2{u, v}, uv_footprint)[0]; };
    const float dhdu = t.bump_scale * (height(uv.x + 0.5f * du, uv.y) - height(uv.x - 0.5f * du, uv.y)) / du;
    const float dhdv = t.bump_scale * (height(uv.x, uv.y + 0.5f * dv) - height(uv.x, uv.y - 0.5f * dv)) / dv;
    Vec3 n = apply_bump(front, dpdu, dpdv, dhdu, dhdv);
    if (!si.outside) n = -n;
    return keep_above(n, si.n_g);
}

// A map on set 0 needs the hit's uv; one on another set finds its own.
bool can_map(const SurfaceInteraction& si, const TextureRef& map) {
    return map.is_set() && (si.has_uv || map.uv_set != 0);
}

}  // namespace

Vec3 apply_normal_map(Vec3 n, Vec3 dpdu, Vec3 dpdv, Vec3 n_map) {
    Vec3 tangent = dpdu - dot(n, dpdu) * n;
    const float t_len = length(tangent);
    if (!(t_len > 0.0f) || !std::isfinite(t_len)) return n;
    tangent = tangent / t_len;
    Vec3 bitangent = dpdv - dot(n, dpdv) * n - dot(tangent, dpdv) * tangent;
    const float b_len = length(bitangent);
    if (!(b_len > 0.0f) || !std::isfinite(b_len)) return n;
    bitangent = bitangent / b_len;
    const Vec3 mapped = n_map.x * tangent + n_map.y * bitangent + n_map.z * n;
    const float len = length(mapped);
    return len > 0.0f && std::isfinite(len) ? mapped / len : n;
}

Vec3 apply_bump(Vec3 n, Vec3 dpdu, Vec3 dpdv, float dhdu, float dhdv) {
    const Vec3 bumped = cross(dpdu + dhdu * n, dpdv + dhdv * n);
    const float len = length(bumped);
    if (!(len > 0.0f) || !std::isfinite(len)) return n;
    return dot(bumped, n) < 0.0f ? -bumped / len : bumped / len;
}

const Material& resolve_material(const Scene& scene, SurfaceInteraction& si, Material& scratch,
                                 float surface_footprint) {
    const Material& m = scene.materials[si.material];
    // Vertex colours (glTF COLOR_0) tint a pbr material's base colour, so
    // such a hit resolves even without textures; other types ignore them.
    Rgba vertex_color;
    const bool colored = m.type == MaterialType::Pbr &&
                         interpolate_color(surface_mesh(scene, si.instance), si.triangle, si.b1, si.b2, vertex_color);
    if (!m.textured && !colored) return m;
    copy_parameters(m, scratch);
    if (surface_footprint > 0.0f && si.has_uv) si.uv_footprint = surface_footprint * uv_per_world(scene, si, 0);
    if (colored) scratch.base_color = m.base_color * rgb_of(vertex_color);
    const MaterialTextures& t = m.textures;
    for (const RgbTextureSlot& slot : kRgbTextureSlots) {
        const TextureRef& ref = t.*slot.texture;
        Vec2 uv;
        float uv_footprint = 0;
        if (!ref.is_set() || !uv_of(scene, si, ref, surface_footprint, uv, uv_footprint)) continue;
        const Vec3 value = scratch.*slot.value * rgb_of(lookup(scene, ref, uv, uv_footprint));
        scratch.*slot.value = clamp_rgb(value, slot.reflectance ? 1.0f : std::numeric_limits<float>::max());
    }
    for (const ScalarTextureSlot& slot : kScalarTextureSlots) {
        const TextureRef& ref = t.*slot.texture;
        Vec2 uv;
        float uv_footprint = 0;
        if (!ref.is_set() || !uv_of(scene, si, ref, surface_footprint, uv, uv_footprint)) continue;
        scratch.*slot.value =
            std::clamp(m.*slot.value * lookup(scene, ref, uv, uv_footprint)[ref.channel & 3u], 0.0f, 1.0f);
    }
    // KHR_materials_clearcoat: the coat's normal is its own map's, else the
    // unmapped n_s; si.n_c is set only where that differs from the base's
    // final n_s, so that a coat without maps on either layer shades as before.
    const bool coat = scratch.type == MaterialType::Pbr && scratch.clearcoat > 0.0f;
    Vec3 n_c = si.n_s;
    if (coat && can_map(si, t.clearcoat_normal_map))
        n_c = normal_mapped(scene, t.clearcoat_normal_map, t.clearcoat_normal_scale, si, surface_footprint);
    // The normal map wins over the bump map, even where it cannot apply.
    if (t.normal_map.is_set()) {
        if (can_map(si, t.normal_map))
            si.n_s = normal_mapped(scene, t.normal_map, t.normal_scale, si, surface_footprint);
    } else if (can_map(si, t.bump_map)) {
        si.n_s = bumped_normal(scene, t, si, surface_footprint);
    }
    si.n_c = coat && !(n_c == si.n_s) ? n_c : Vec3{};
    return scratch;
}

Vec3 emission_at(const Scene& scene, const Material& material, std::uint32_t triangle, Vec3 y, std::uint32_t instance) {
    const TextureRef& ref = material.textures.ke;
    if (!ref.is_set()) return material.ke;
    // In an instance, y's barycentrics are found in the mesh's own
    // coordinates (the same weights: the transform is affine).
    const TriangleMesh& mesh = surface_mesh(scene, instance);
    if (instance != kNoInstance) y = transform_point(scene.instances[instance].world_to_object, y);
    Vec2 uv{0.0f, 0.0f};
    float b1 = 0, b2 = 0;
    if (ref.uv_set != 0) {
        // A set the triangle lacks leaves the constant alone (as resolve_material does).
        if (!point_barycentrics(mesh, triangle, y, b1, b2) ||
            !interpolate_uv_set(mesh, ref.uv_set, triangle, b1, b2, uv))
            return material.ke;
    } else if (mesh.has_uvs() && point_barycentrics(mesh, triangle, y, b1, b2)) {
        interpolate_uv(mesh, triangle, b1, b2, uv);
    }
    return clamp_rgb(material.ke * rgb_of(lookup(scene, ref, uv, 0.0f)), std::numeric_limits<float>::max());
}

}  // namespace sombra
