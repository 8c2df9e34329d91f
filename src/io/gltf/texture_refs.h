// What a glTF material says about its textures (spec §12, §13), as plain
// data: the glTF loader fills these from the file, and gltf_textures.cpp
// turns them into the materials' texture slots (scene/material.h).
#pragma once

#include <string>

#include "core/vec2.h"

namespace sombra {

// A glTF sampler's wrapS / wrapT.
enum class GltfWrap { Repeat, ClampToEdge, MirroredRepeat };

// One textureInfo of a glTF material.
struct GltfTextureRef {
    int texture = -1;  // index into the file's textures; -1: the slot is empty
    int image = -1;    // the texture's source image; -1 when it names none
    std::string uri;   // the image's uri as written (relative to the file's folder); "" when embedded
    int texcoord = 0;  // which TEXCOORD_n the lookup uses (KHR_texture_transform may override it)
    GltfWrap wrap_s = GltfWrap::Repeat;
    GltfWrap wrap_t = GltfWrap::Repeat;
    // KHR_texture_transform, in glTF's uv convention (v = 0 at the image's top):
    // uv' = translate(offset) · rotate(rotation) · scale(scale) · uv.
    Vec2 offset{0, 0};
    float rotation = 0;  // radians, counter-clockwise in uv
    Vec2 scale{1, 1};
    float strength = 1;  // normalTexture.scale, clearcoatNormalTexture.scale, occlusionTexture.strength; 1 otherwise

    bool present() const { return texture >= 0; }
};

// glTF alphaMode (spec §13: BLEND is treated as MASK with cutoff 0.5).
enum class AlphaMode { Opaque, Mask, Blend };

// Per material: every texture slot of glTF 2.0's metallic-roughness model and
// what alpha needs besides the textures.
struct GltfMaterialTextures {
    GltfTextureRef base_color;           // RGB times base_color; A is alpha
    GltfTextureRef metallic_roughness;   // roughness from G, metallic from B
    GltfTextureRef normal;               // tangent space
    GltfTextureRef emissive;             // times ke
    GltfTextureRef occlusion;            // ignored by the spec (§13), kept for completeness
    GltfTextureRef specular;             // KHR_materials_specular: A times specular
    GltfTextureRef specular_color;       // KHR_materials_specular: RGB (sRGB) times specular_color
    GltfTextureRef transmission;         // KHR_materials_transmission: R times transmission
    GltfTextureRef clearcoat;            // KHR_materials_clearcoat: R times clearcoat
    GltfTextureRef clearcoat_roughness;  // KHR_materials_clearcoat: G times clearcoat_roughness
    GltfTextureRef clearcoat_normal;     // KHR_materials_clearcoat: the coat's tangent-space normal
    GltfTextureRef sheen_color;          // KHR_materials_sheen: RGB (sRGB) times sheen_color
    GltfTextureRef sheen_roughness;      // KHR_materials_sheen: A times sheen_roughness
    AlphaMode alpha_mode = AlphaMode::Opaque;
    float alpha_cutoff = 0.5f;  // MASK: cut out where alpha < cutoff
    float base_alpha = 1.0f;    // baseColorFactor's A

    bool any() const {
        return base_color.present() || metallic_roughness.present() || normal.present() || emissive.present() ||
               occlusion.present() || specular.present() || specular_color.present() || transmission.present() ||
               clearcoat.present() || clearcoat_roughness.present() || clearcoat_normal.present() ||
               sheen_color.present() || sheen_roughness.present();
    }
};

}  // namespace sombra
