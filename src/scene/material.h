// Surface materials of spec §5 and §11, as plain data. The BSDFs that
// evaluate and sample them live in render/bsdf/bsdf.h (render/bsdf/brdf.h holds the
// version-1 BRDF terms that the direct integrator evaluates).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "scene/texture.h"
#include "scene/texture_mipmap.h"

namespace sombra {

enum class MaterialType {
    Diffuse,     // Lambert, kd / π (§5)
    Phong,       // energy-normalised modified Phong (§5)
    Mirror,      // perfect specular reflection, reflectance kr (§11)
    Dielectric,  // smooth glass: Fresnel reflection and refraction, ior, kt (§11)
    Conductor,   // GGX microfacet metal, Schlick Fresnel from ks, roughness (§11)
    Pbr,         // glTF 2.0 metallic–roughness: base_color, metallic, roughness, ior (§11)
    // A boundary of a medium that rays cross unchanged (spec §26's
    // "interface", Cycles' volume-only objects): no BSDF, no emission.
    Interface,
};

// Marks a material parameter without a texture.
inline constexpr std::uint32_t kNoTexture = 0xffffffffu;

// An affine map of texture coordinates in sombra's convention (v = 0 at the
// image's bottom row): uv ↦ (uu·u + uv·v + u0, vu·u + vv·v + v0). What a
// glTF KHR_texture_transform becomes (gltf_textures.cpp converts it from
// glTF's v-down convention); the default is the identity.
struct UvTransform {
    float uu = 1, uv = 0, u0 = 0;
    float vu = 0, vv = 1, v0 = 0;
};

inline Vec2 apply_uv_transform(const UvTransform& t, Vec2 uv) {
    return {t.uu * uv.x + t.uv * uv.y + t.u0, t.vu * uv.x + t.vv * uv.y + t.v0};
}

// A material parameter's image (spec §12): an index into the scene's texture
// table (Scene::textures; LoadedMesh::textures for a mesh file's own), how
// lookups wrap, for a scalar parameter which channel it reads, and where
// the hit's uv is moved before the lookup.
struct TextureRef {
    std::uint32_t texture = kNoTexture;
    TextureWrap wrap_u = TextureWrap::Repeat;
    TextureWrap wrap_v = TextureWrap::Repeat;
    std::uint8_t channel = 0;  // scalar parameters: 0 r, 1 g, 2 b, 3 a
    // Which texture coordinate set the lookup reads (glTF texCoord; spec
    // §24): 0 is TriangleMesh::uvs, k < kUvSets its extra_uvs[k − 1]. On a
    // triangle without set k ≥ 1 the parameter keeps its constant.
    std::uint8_t uv_set = 0;
    // Lookups read at apply_uv_transform(uv_transform, uv) when set, else at
    // the hit's uv itself (so untransformed lookups never pay for, nor round
    // through, an identity map).
    bool transformed = false;
    UvTransform uv_transform{};
    bool is_set() const { return texture != kNoTexture; }
};

// The textures of one material. A textured RGB parameter's value at a hit is
// the material's constant (the scale, 1 when a file gives none) times the
// texel's RGB; a textured scalar's is the constant times the chosen channel.
struct MaterialTextures {
    TextureRef kd, ks, kr, kt, ke, base_color, specular_color, sheen_color;  // RGB parameters (see kRgbTextureSlots)
    TextureRef roughness, metallic, specular, transmission, clearcoat, clearcoat_roughness,
        sheen_roughness;  // scalar parameters (see kScalarTextureSlots)
    // Tangent-space normal map (OpenGL convention, +y toward increasing v):
    // data, n = normalize((2·texel − 1) ⊙ (normal_scale, normal_scale, 1))
    // (glTF normalTexture.scale; 1 elsewhere). Wins over the bump map.
    TextureRef normal_map;
    float normal_scale = 1;
    // KHR_materials_clearcoat's clearcoatNormalTexture: the coat's own
    // tangent-space normal map, read as normal_map is (its scale
    // clearcoat_normal_scale). Unset: the coat has no normal mapping at all
    // (neither this nor the base's maps), as the extension says.
    TextureRef clearcoat_normal_map;
    float clearcoat_normal_scale = 1;
    // Height map (MTL bump): its first channel times bump_scale is a
    // displacement along n_s in world units (as pbrt's bump mapping).
    TextureRef bump_map;
    float bump_scale = 1;
    // Cut-out (spec §12, §13, scene/cutout.h): when alpha_test is set, the
    // surface does not exist where its alpha is below alpha_cutoff. Alpha is
    // alpha_factor (glTF's baseColorFactor A) times the alpha texture's
    // channel (the A channel, else the first) when one is set, times the
    // vertex colour's alpha (glTF COLOR_0) on triangles that have colours.
    bool alpha_test = false;
    TextureRef alpha;
    float alpha_cutoff = 0.5f;
    float alpha_factor = 1.0f;
};

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Vec3 kd{0.8f};        // diffuse albedo, each channel in [0, 1]
    Vec3 ks{0.0f};        // Phong specular albedo; Conductor: reflectance at normal incidence
    float shininess = 1;  // Phong exponent n >= 0 (Phong only)
    Vec3 ke{0.0f};        // emitted radiance (two-sided unless emits_front_only)
    Vec3 kr{1.0f};        // Mirror reflectance, each channel in [0, 1]
    Vec3 kt{1.0f};        // Dielectric transmission tint, each channel in [0, 1]
    float ior =
        1.5f;  // Dielectric index of refraction inside, > 1 (outside is 1); Pbr: sets f0 = ((1 − ior)/(1 + ior))²
    float roughness = 0;    // Conductor and Pbr roughness r in [0, 1]; GGX α = r²
    Vec3 base_color{1.0f};  // Pbr base colour, each channel in [0, 1]: diffuse albedo, and f0 of the metal
    float metallic = 0.0f;  // Pbr metalness m in [0, 1]: the mix (1 − m)·dielectric + m·metal
    // Pbr, glTF's KHR_materials_specular: the dielectric layer's Fresnel runs
    // from f0 = min(((1 − ior)/(1 + ior))² · specular_color, 1) · specular at
    // normal incidence to specular at grazing; specular in [0, 1], the colour
    // ≥ 0 (it may exceed 1). The defaults leave glTF's core model unchanged.
    float specular = 1.0f;
    Vec3 specular_color{1.0f};
    // Pbr, glTF's KHR_materials_transmission: the fraction in [0, 1] of the
    // light that enters the dielectric base (what its Fresnel layer does not
    // reflect) and goes through the surface, tinted by base_color, rather
    // than being reflected diffusely. 0 (the default) is glTF's core model.
    float transmission = 0.0f;
    // Pbr, glTF's KHR_materials_volume: thickness > 0 says the mesh bounds a
    // volume of index `ior`, so transmission refracts at each interface and
    // light travelling inside is attenuated as exp(−σ_a·d), σ_a =
    // −ln(attenuation_color)/attenuation_distance (Beer–Lambert). 0 (the
    // default): a thin wall, which transmission passes straight through.
    // Only sombra's glTF reader sets these (scene files have no keys for them).
    float thickness = 0.0f;
    Vec3 attenuation_color{1.0f};                                         // each channel in (0, 1]
    float attenuation_distance = std::numeric_limits<float>::infinity();  // > 0; infinite: no attenuation
    // Pbr, glTF's KHR_materials_clearcoat: a GGX dielectric coat (ior 1.5)
    // of strength `clearcoat` in [0, 1] and roughness in [0, 1] (α = r²)
    // over the whole material. 0 (the default): no coat. glTF only.
    float clearcoat = 0.0f;
    float clearcoat_roughness = 0.0f;
    // Pbr, glTF's KHR_materials_sheen: a layer of "Charlie" micro-fibres
    // (render/bsdf/bsdf_pbr_sheen.cpp) of colour sheen_color (each channel in
    // [0, 1]) and roughness in [0, 1] (α = r²) between the base and the coat.
    // A black colour (the default) is no layer at all. glTF only.
    Vec3 sheen_color{0.0f};
    float sheen_roughness = 0.0f;
    // Quad lights (§10) emit only toward the side their winding normal
    // (v1 − v0) × (v2 − v0) points to, and are black from behind.
    bool emits_front_only = false;
    MaterialTextures textures{};
    // any_texture(textures), set by whoever fills `textures` (the scene's
    // assembly of mesh files sets it again): renderers resolve a textured
    // material at each hit (render/shading.h), and only a textured one.
    bool textured = false;
};

// The parameters that may come from a texture, by their scene-file key. A
// new RGB or scalar parameter gets its texture with one line here (and its
// TextureRef in MaterialTextures).
// `reflectance` parameters are clamped to [0, 1] at a hit (an EXR texel may
// exceed 1); the others (ke, a radiance) only to >= 0.
struct RgbTextureSlot {
    const char* key;
    Vec3 Material::*value;
    TextureRef MaterialTextures::*texture;
    bool reflectance;
};
inline constexpr RgbTextureSlot kRgbTextureSlots[] = {
    {"kd", &Material::kd, &MaterialTextures::kd, true},
    {"ks", &Material::ks, &MaterialTextures::ks, true},
    {"kr", &Material::kr, &MaterialTextures::kr, true},
    {"kt", &Material::kt, &MaterialTextures::kt, true},
    {"ke", &Material::ke, &MaterialTextures::ke, false},
    {"base_color", &Material::base_color, &MaterialTextures::base_color, true},
    {"specular_color", &Material::specular_color, &MaterialTextures::specular_color, false},
    {"sheen_color", &Material::sheen_color, &MaterialTextures::sheen_color, true},
};
struct ScalarTextureSlot {
    const char* key;
    float Material::*value;
    TextureRef MaterialTextures::*texture;
};
inline constexpr ScalarTextureSlot kScalarTextureSlots[] = {
    {"roughness", &Material::roughness, &MaterialTextures::roughness},
    {"metallic", &Material::metallic, &MaterialTextures::metallic},
    {"specular", &Material::specular, &MaterialTextures::specular},
    {"transmission", &Material::transmission, &MaterialTextures::transmission},
    {"clearcoat", &Material::clearcoat, &MaterialTextures::clearcoat},
    {"clearcoat_roughness", &Material::clearcoat_roughness, &MaterialTextures::clearcoat_roughness},
    {"sheen_roughness", &Material::sheen_roughness, &MaterialTextures::sheen_roughness},
};

// The image of `ref` (set) in `table` at the hit's uv, moved by the
// reference's uv transform when it has one: where every texture lookup of a
// material parameter goes, so that how a reference reads its image is decided
// in one place.
inline Rgba eval_texture_ref(const std::vector<Texture>& table, const TextureRef& ref, Vec2 uv) {
    if (ref.transformed) uv = apply_uv_transform(ref.uv_transform, uv);
    return eval_texture(table[ref.texture], uv, ref.wrap_u, ref.wrap_v);
}

// eval_texture_ref filtered for a footprint `uv_footprint` wide in uv units
// (render/ray_cone.h): the trilinear lookup of the reference's mip pyramid at
// that footprint's level (scene/texture_mipmap.h). A footprint of 0, or a
// texture without a pyramid, reads as eval_texture_ref, bit for bit. A
// transformed reference moves uv as eval_texture_ref does and scales the
// footprint by the transform's own scale, √|det|.
inline Rgba eval_texture_ref_filtered(const std::vector<Texture>& table, const TextureRef& ref, Vec2 uv,
                                      float uv_footprint) {
    if (!(uv_footprint > 0.0f)) return eval_texture_ref(table, ref, uv);
    if (ref.transformed) {
        const UvTransform& m = ref.uv_transform;
        uv = apply_uv_transform(m, uv);
        uv_footprint *= std::sqrt(std::fabs(m.uu * m.vv - m.uv * m.vu));
    }
    const Texture& t = table[ref.texture];
    return eval_texture_lod(t, uv, mip_lod(t, uv_footprint), ref.wrap_u, ref.wrap_v);
}

// True when some slot, the normal map, the bump map or the alpha of `t` is set.
inline bool any_texture(const MaterialTextures& t) {
    for (const RgbTextureSlot& slot : kRgbTextureSlots)
        if ((t.*slot.texture).is_set()) return true;
    for (const ScalarTextureSlot& slot : kScalarTextureSlots)
        if ((t.*slot.texture).is_set()) return true;
    return t.normal_map.is_set() || t.clearcoat_normal_map.is_set() || t.bump_map.is_set() || t.alpha.is_set();
}

// Copies every field of `from` but its name into `to`: what a hit's resolved
// material (render/shading.h) starts from, without the allocation a long
// name's copy would cost per ray. The binding lists every field, so that a
// field added to Material fails to compile here until it is copied too.
inline void copy_parameters(const Material& from, Material& to) {
    const auto& [name, type, kd, ks, shininess, ke, kr, kt, ior, roughness, base_color, metallic, specular,
                 specular_color, transmission, thickness, attenuation_color, attenuation_distance, clearcoat,
                 clearcoat_roughness, sheen_color, sheen_roughness, emits_front_only, textures, textured] = from;
    static_cast<void>(name);
    to.type = type;
    to.kd = kd;
    to.ks = ks;
    to.shininess = shininess;
    to.ke = ke;
    to.kr = kr;
    to.kt = kt;
    to.ior = ior;
    to.roughness = roughness;
    to.base_color = base_color;
    to.metallic = metallic;
    to.specular = specular;
    to.specular_color = specular_color;
    to.transmission = transmission;
    to.thickness = thickness;
    to.attenuation_color = attenuation_color;
    to.attenuation_distance = attenuation_distance;
    to.clearcoat = clearcoat;
    to.clearcoat_roughness = clearcoat_roughness;
    to.sheen_color = sheen_color;
    to.sheen_roughness = sheen_roughness;
    to.emits_front_only = emits_front_only;
    to.textures = textures;
    to.textured = textured;
}

// Calls f(ref) for every TextureRef of `t` (to remap or check their indices).
template <typename F>
void for_each_texture_ref(MaterialTextures& t, F&& f) {
    for (const RgbTextureSlot& slot : kRgbTextureSlots) f(t.*slot.texture);
    for (const ScalarTextureSlot& slot : kScalarTextureSlots) f(t.*slot.texture);
    f(t.normal_map);
    f(t.clearcoat_normal_map);
    f(t.bump_map);
    f(t.alpha);
}

// True when a Phong material can reflect more light than it receives: kd + ks
// exceeds 1 in some channel (spec §5 asks for a warning, from scenes and MTL alike).
inline bool breaks_energy_conservation(const Material& m) {
    return m.type == MaterialType::Phong && max_component(m.kd + m.ks) > 1;
}

// The absorption coefficient σ_a (1/world unit, per channel) of the volume
// a pbr material bounds (KHR_materials_volume): −ln(attenuation_color) /
// attenuation_distance; 0 for a thin-walled material (thickness 0), an
// infinite distance or a white colour.
inline Vec3 volume_absorption(const Material& m) {
    if (!(m.thickness > 0.0f) || !(m.attenuation_distance < std::numeric_limits<float>::infinity())) return Vec3{0.0f};
    const auto sigma = [&m](float c) {
        return c >= 1.0f ? 0.0f : -std::log(std::max(c, 1e-30f)) / m.attenuation_distance;
    };
    return {sigma(m.attenuation_color.x), sigma(m.attenuation_color.y), sigma(m.attenuation_color.z)};
}

// exp(−σ_a·d): the fraction of light that crosses `distance` (world units)
// inside the volume of m (volume_absorption), per channel.
inline Vec3 volume_transmittance(const Material& m, float distance) {
    const Vec3 sigma = volume_absorption(m);
    return {std::exp(-sigma.x * distance), std::exp(-sigma.y * distance), std::exp(-sigma.z * distance)};
}

// True when the material emits light (some ke component > 0).
inline bool is_emissive(const Material& m) { return max_component(m.ke) > 0.0f; }

// What a face with no material gets (spec §5): diffuse, kd = 0.8 grey.
inline Material default_material() { return Material{"default", MaterialType::Diffuse, Vec3{0.8f}, {}, 1, {}}; }

}  // namespace sombra
