// Image textures (spec §12) as plain data: decoded once, at load, into
// contiguous float arrays; looked up bilinearly at render time. The scene
// holds one table of them (Scene::textures; a mesh file's reader fills its
// own, LoadedMesh::textures in io/mesh_file.h); materials name entries by
// index (TextureRef, scene/material.h).
//
// For a reader (OBJ/MTL, scene files, glTF): decode the image with
// io/images/texture_image.h, told whether it holds colours (sRGB-decoded when
// 8 or 16 bit) or data (used as stored), append the result to the table
// (add_texture) and point a material's TextureRef at its index, with the
// sampler's wrap modes. Texture coordinates follow OBJ: v = 0 is the
// image's BOTTOM row. glTF's TEXCOORD_0 has v = 0 at the top: its loader
// stores (u, 1 − v) in TriangleMesh::uvs, which also keeps the tangent
// frame's +y toward increasing (stored) v as normal maps expect (KHR_texture_
// transform is applied before the flip).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "core/vec3.h"

namespace sombra {

// How an image's values become texture values.
enum class TextureEncoding : std::uint8_t {
    Color,  // 8- and 16-bit colour channels sRGB-decoded (alpha never); EXR and HDR as stored (linear)
    Data,   // every channel as stored, 8- and 16-bit scaled to [0, 1]: roughness, metallic, normal, height, alpha
};

// What a lookup outside [0, 1) does along one axis (glTF sampler wrapS/wrapT).
enum class TextureWrap : std::uint8_t {
    Repeat,          // the default: u and u + 1 look the same
    Clamp,           // the edge texels extend outwards
    MirroredRepeat,  // every other repetition mirrored
};

// One level of a texture's mip pyramid (scene/texture_mipmap.h): a smaller
// copy of the image, laid out as Texture::texels, with the texture's channels.
struct TextureLevel {
    int width = 0, height = 0;
    std::vector<float> texels;
};

struct Texture {
    // The file's path (or a loader's name for an embedded image, e.g.
    // "model.glb: /images/3"): messages name it, and textures with the same
    // source and encoding are shared when meshes join a scene.
    std::string source;
    TextureEncoding encoding = TextureEncoding::Color;
    int width = 0, height = 0;
    int channels = 0;  // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
    // Row-major, the image's TOP row first (as files store it), `channels`
    // floats per texel: finite and >= 0 (8- and 16-bit ones also <= 1).
    std::vector<float> texels;
    // Levels 1, 2, … of the mip pyramid, each about half the previous one's
    // size per side (level 0 is `texels`). Empty unless build_mip_pyramid
    // (scene/texture_mipmap.h) ran: only renders with mip-mapping build it.
    std::vector<TextureLevel> mip_levels;
};

// sRGB's electro-optical transfer function, exactly as IEC 61966-2-1 writes
// it: c/12.92 up to 0.04045, else ((c + 0.055)/1.055)^2.4; c in [0, 1].
float srgb_to_linear(float c);
// The same for an integer code of an image with values 0 … max_code (255 or
// 65535): the formula evaluated in double at code / max_code, then rounded.
float srgb_decode(unsigned code, unsigned max_code);

// A texture's RGBA at a point: grey images give r = g = b; images without
// alpha give a = 1.
using Rgba = std::array<float, 4>;

// The bilinear lookup of spec §12 at full resolution: texel (i, j), i from
// the left and j from the BOTTOM row, has its centre at ((i + ½)/W, (j + ½)/H);
// uv between centres blends the four around it, and beyond the outermost
// centres `wrap_u`, `wrap_v` decide which texels are the neighbours.
// Non-finite coordinates read as 0. `t` must hold at least one texel.
Rgba eval_texture(const Texture& t, Vec2 uv, TextureWrap wrap_u = TextureWrap::Repeat,
                  TextureWrap wrap_v = TextureWrap::Repeat);

// The same lookup on any grid of texels laid out as Texture::texels (a
// texture's own, or one level of its pyramid): `width` × `height` texels of
// `channels` floats, top row first.
Rgba eval_texels(const float* texels, int width, int height, int channels, Vec2 uv, TextureWrap wrap_u,
                 TextureWrap wrap_v);

inline Vec3 rgb_of(const Rgba& c) { return {c[0], c[1], c[2]}; }

// The index of `texture` in `table`, appending it unless an entry with the
// same source and encoding is there already (then that entry's index).
std::uint32_t add_texture(std::vector<Texture>& table, const Texture& texture);
// The same for a texture that is not needed afterwards (a loader's freshly
// decoded one): appended by moving its texels rather than copying them.
std::uint32_t add_texture(std::vector<Texture>& table, Texture&& texture);

}  // namespace sombra
