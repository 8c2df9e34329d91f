// Mip pyramids of image textures, for renders that filter lookups by the ray's
// footprint (--texture-filter mipmap; spec §12 keeps full-resolution bilinear
// lookups the default). Plain data: a pyramid is Texture::mip_levels, built
// once after loading, read by eval_texture_lod.
//
// Each level halves the previous one's sides, rounding down (7 × 5 → 3 × 2),
// and stops at the first level whose shorter side is 1: every texel of a new
// level is the exact box average of the previous level's texels under its
// area, so a power-of-two side averages 2 × 2 blocks and an odd side spreads
// each output texel over 2 + 1/m input texels (m the new side), weighting the
// ones it covers in part by the part it covers. The texture's mean is kept at
// every level, and the levels together hold at most a third of the base's
// values (each is at most a quarter of the one before): the pyramid costs at
// most 4/3 of the texture. A very long texture (4096 × 16) stops at a level
// longer than 1 texel (256 × 1); footprints beyond it read that level.
#pragma once

#include <vector>

#include "core/vec2.h"
#include "scene/texture.h"

namespace sombra {

// Fills t.mip_levels (replacing what was there) from t.texels as described
// above. A texture with a side of 1 gets no levels.
void build_mip_pyramid(Texture& t);

// build_mip_pyramid for every texture of the table, in parallel (textures,
// and rows within a level): the result does not depend on the thread count.
void build_mip_pyramids(std::vector<Texture>& table);

// The level of detail λ for a footprint `uv_footprint` wide in uv units
// (the width on the surface that one pixel's cone covers, in texture
// coordinates): log2 of the footprint in texels of `t`, i.e. of
// uv_footprint · √(width · height). λ = 0 is a texel per footprint (full
// resolution); λ = 2 is four texels across it, level 2's texel size. Not
// clamped; a footprint of 0 gives −∞.
float mip_lod(const Texture& t, float uv_footprint);

// The trilinear lookup at level of detail `lod`: the bilinear lookups
// (eval_texels) of levels ⌊lod⌋ and ⌊lod⌋ + 1 blended by lod's fraction.
// lod <= 0 or NaN, or no pyramid built, is eval_texture itself (bit for bit);
// lod at or beyond the coarsest level reads the coarsest level.
Rgba eval_texture_lod(const Texture& t, Vec2 uv, float lod, TextureWrap wrap_u = TextureWrap::Repeat,
                      TextureWrap wrap_v = TextureWrap::Repeat);

}  // namespace sombra
