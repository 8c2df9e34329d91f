// The environment light of spec §10: radiance arriving from infinitely far
// away, by direction only. Either a constant colour (the scene's
// "background" under the path integrator) or an equirectangular map.
//
// Frames: directions are unit vectors in world space, y up, pointing from the
// scene toward the sky (the direction a ray travels to escape). The map is
// read at d' = R_y(−θ)·d, θ = rotate_y_degrees (right-handed about +y), with
//   u = 0.5 + atan2(d'.x, −d'.z) / (2π),   v = acos(d'.y) / π,
// (u, v) = (0, 0) the top-left corner of the image: −z sees the map's centre,
// +y its top row. Lookups are bilinear with texel centres at
// ((i + ½)/W, (j + ½)/H), wrapping in u and clamped in v.
#pragma once

#include "core/vec3.h"
#include "render/lights/distribution.h"
#include "scene/hdr_image.h"

namespace sombra {

struct Environment {
    Vec3 constant{0.0f};  // the radiance from every direction when there is no map
    HdrImage image;       // the map; empty (width 0) for a constant environment
    float scale = 1;      // radiance = scale × texel
    float rotate_y_degrees = 0;
    float cos_rotate = 1, sin_rotate = 0;  // of rotate_y_degrees
    // Over the map's texels, row 0 at v = 0: proportional to the maximum
    // luminance in each texel's 3×3 neighbourhood (the texels its bilinear
    // lookups can reach) × sin θ at its centre, plus a floor for any texel
    // with radiance nearby, so that the pdf is > 0 wherever eval is.
    Distribution2D distribution;
};

Environment make_constant_environment(Vec3 radiance);
// `image` must be non-empty with finite, non-negative pixels (read_hdr_image
// guarantees it); scale ≥ 0.
Environment make_map_environment(HdrImage image, float scale, float rotate_y_degrees);

// True for an image environment, false for a constant colour.
bool has_map(const Environment& env);

// True when no direction receives any radiance: the environment then needs
// no sampling, and sample_environment returns false.
bool is_black(const Environment& env);

// The radiance arriving along -direction, i.e. from the sky in `direction`
// (unit, world). Finite and non-negative.
Vec3 eval_environment(const Environment& env, Vec3 direction);

struct EnvironmentSample {
    Vec3 direction;  // unit, world, toward the sky
    Vec3 radiance;   // eval_environment(env, direction)
    float pdf = 0;   // w.r.t. solid angle: pdf_environment(env, direction)
};
// A direction distributed as pdf_environment, from u1, u2 uniform in [0, 1).
// False (out untouched beyond garbage) when the environment is black or the
// sample falls where the pdf is 0 (the map's poles): count it as no light.
bool sample_environment(const Environment& env, float u1, float u2, EnvironmentSample& out);

// The solid-angle density with which sample_environment returns `direction`:
// 1/(4π) for a constant environment, pdf_uv / (2π² sin θ) for a map (0 at
// the poles, sin θ = 0, and for a black environment). Never NaN or Inf.
float pdf_environment(const Environment& env, Vec3 direction);

// ∫ luminance(eval(d)) dω over the sphere (W/(m²·sr)·sr), using the texels as
// piecewise constant. Used to weigh the environment against area lights when
// picking a light to sample: its power is this times π·R², R the radius of
// the scene's bounding sphere (the caller multiplies). 0 when black.
float environment_power_proxy(const Environment& env);

}  // namespace sombra
