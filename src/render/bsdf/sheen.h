// The "Charlie" sheen lobe of glTF's KHR_materials_sheen (Estevez and
// Kulla 2017, "Production Friendly Microfacet Sheen BRDF"), as the
// extension's implementation notes write it, and its directional albedo.
//
//   f_sheen = D(h)·V(ωo, ωi)                    (1/sr, sheen colour 1)
//   D(h)    = (2 + 1/α)·sin(θ_h)^(1/α) / (2π),  α = r² (r: sheen roughness)
//   V       = 1 / ((1 + Λ(cos θ_o) + Λ(cos θ_i))·4·cos θ_o·cos θ_i)
//
// Λ is the paper's fitted curve: Λ(μ) = exp(L(μ)) for μ < ½, else
// exp(2L(½) − L(1 − μ)), L(x) = a/(1 + b·x^c) + d·x + e with a…e
// interpolated between the paper's two fits by (1 − α)². This is the
// visibility the extension's notes give first and the Khronos sample viewer
// uses (not Ashikhmin's, which the notes say breaks albedo scaling), so the
// layer conserves energy with the albedo below.
//
// Frame: directions local to the shading frame (n_s = +z). Internal to render/.
#pragma once

#include "core/vec3.h"

namespace sombra {

// The smallest sheen roughness the lobe uses: r = 0 (the extension's
// default) is a distribution concentrated on the horizon, 1/α infinite; at
// 0.01 (α = 10⁻⁴) the lobe is already black unless both directions graze
// within a degree or so, which is what r = 0 means. Keeps D and V finite.
inline constexpr float kMinSheenRoughness = 0.01f;

// The lobe D·V for roughness r (clamped to [kMinSheenRoughness, 1]), local
// directions; 0 unless wo.z > 0 and wi.z > 0.
float eval_sheen_lobe(Vec3 wo, Vec3 wi, float roughness);

// E(μ, r) = ∫ D·V·cos θ_i dωi over the upper hemisphere: the lobe's
// directional albedo at cos θ_o = μ, read bilinearly from a 32 × 32 table
// over μ ∈ [0, 1] and r ∈ [0, 1] (both clamped), built on first use by
// make_sheen_albedo_table (~30 ms; thread-safe, immutable after).
float sheen_albedo(float cos_theta, float roughness);

// The table: E at μ_i = i/31, r_j = j/31 (μ_0 and r_0 evaluated at 10⁻³ and
// kMinSheenRoughness), by sheen_albedo_integral. E exceeds 1 at grazing
// views of smooth sheens (16.8 at μ = 10⁻³, r ≤ 0.01; 1.6 at μ = 1/31,
// r = 1/31): the extension's lobe itself reflects more than it receives
// there, and the layer's albedo scaling (clamped at 0) can only remove the
// base beneath it.
inline constexpr int kSheenTableSize = 32;
struct SheenAlbedoTable {
    float e[kSheenTableSize][kSheenTableSize];  // [roughness index][μ index]
};
SheenAlbedoTable make_sheen_albedo_table();

// E(μ, r) by a product midpoint rule in double precision over the
// hemisphere of ωi, cos θ_i = t² (which crowds nodes toward the horizon,
// where the lobe lives for small r) and φ_i ∈ [0, π] (the integrand is even
// in φ): `nt` × `nphi` nodes.
double sheen_albedo_integral(double mu, double roughness, int nt, int nphi);

}  // namespace sombra
