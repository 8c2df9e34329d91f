// An independent reference for tests of spec §11's `pbr` material: the glTF
// 2.0 specification's Appendix B (with KHR_materials_specular's
// fresnel_mix) written out in double precision, in its own
// notation (N, V, L, H and the Heaviside χ⁺), from the formulas of the
// specification rather than from render/bsdf/microfacet.h. One colour channel at a
// time. Header-only and for tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sombra::pbr_reference {

struct Params {
    double base = 1;  // base_color, one channel
    double metallic = 0;
    double roughness = 0.5;
    double ior = 1.5;
    // KHR_materials_specular: the strength, this channel's specular colour
    // and the colour's largest channel (its max_value of the Fresnel term
    // belongs to the channel with the largest colour).
    double specular = 1;
    double specular_color = 1;
    double specular_color_max = 1;
};

// KHR_materials_specular's dielectric_fresnel for a colour channel c at
// fresnel_w = (1 − |V·H|)⁵: mix(min(f0_ior · c, 1) · specular, specular, fresnel_w).
inline double dielectric_fresnel(const Params& p, double color, double fresnel_w) {
    const double f0 = std::min(std::pow((1 - p.ior) / (1 + p.ior), 2) * color, 1.0) * p.specular;
    return f0 + (p.specular - f0) * fresnel_w;
}

struct Dir {
    double x, y, z;
};

inline double dot(Dir a, Dir b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double heaviside(double x) { return x > 0 ? 1.0 : 0.0; }

// Appendix B's material = mix(dielectric_brdf, metal_brdf, metallic) for
// unit V (towards the viewer) and L (towards the light), N = +z; 0 unless
// both are above the surface. Roughness must be > 0 (a rough lobe).
inline double brdf(const Params& p, Dir v, Dir l) {
    if (v.z <= 0 || l.z <= 0) return 0;
    constexpr double pi = std::numbers::pi;
    const double a = p.roughness * p.roughness, a2 = a * a;
    Dir h{v.x + l.x, v.y + l.y, v.z + l.z};
    const double len = std::sqrt(dot(h, h));
    h = {h.x / len, h.y / len, h.z / len};
    const double n_h = h.z, n_l = l.z, n_v = v.z, v_h = dot(v, h), l_h = dot(l, h);
    const double d_term = a2 * heaviside(n_h) / (pi * std::pow(n_h * n_h * (a2 - 1) + 1, 2));
    const double vis = heaviside(l_h) * heaviside(v_h) /
                       (2 * (std::fabs(n_v) * std::sqrt(a2 + (1 - a2) * n_l * n_l) +
                             std::fabs(n_l) * std::sqrt(a2 + (1 - a2) * n_v * n_v)));
    const double specular_brdf = vis * d_term;
    const double diffuse_brdf = p.base / pi;
    const double fresnel_w = std::pow(1 - std::fabs(v_h), 5);
    const double fresnel = dielectric_fresnel(p, p.specular_color, fresnel_w);
    const double fresnel_max = dielectric_fresnel(p, p.specular_color_max, fresnel_w);
    const double dielectric_brdf = (1 - fresnel_max) * diffuse_brdf + fresnel * specular_brdf;
    const double metal_brdf = (p.base + (1 - p.base) * fresnel_w) * specular_brdf;
    return (1 - p.metallic) * dielectric_brdf + p.metallic * metal_brdf;
}

// The diffuse part alone, (1 − metallic)(1 − F)·base/π: what is left of the
// BRDF when the specular part is a delta (roughness 0).
inline double diffuse_part(const Params& p, Dir v, Dir l) {
    if (v.z <= 0 || l.z <= 0) return 0;
    Dir h{v.x + l.x, v.y + l.y, v.z + l.z};
    const double len = std::sqrt(dot(h, h));
    const double v_h = dot(v, {h.x / len, h.y / len, h.z / len});
    const double fresnel_max = dielectric_fresnel(p, p.specular_color_max, std::pow(1 - std::fabs(v_h), 5));
    return (1 - p.metallic) * (1 - fresnel_max) * p.base / std::numbers::pi;
}

// KHR_materials_transmission's thin-wall transmission for V above and L
// below the surface (N = +z), as the extension writes it:
// (1 − metallic) · transmission · (1 − F_max) · base · V_T · D_T with the
// transmission half vector H_T = normalize(V − 2(N·L)N + L), V_T the
// separable Smith form of its implementation notes, F at |V·H_T|.
// Roughness must be > 0.
inline double thin_transmission(const Params& p, double transmission, Dir v, Dir l) {
    if (v.z <= 0 || l.z >= 0) return 0;
    constexpr double pi = std::numbers::pi;
    const double a = p.roughness * p.roughness, a2 = a * a;
    Dir h{v.x + l.x, v.y + l.y, v.z - l.z};
    const double len = std::sqrt(dot(h, h));
    h = {h.x / len, h.y / len, h.z / len};
    const double n_h = h.z, n_l = l.z, n_v = v.z;
    const double d_t = a2 * heaviside(n_h) / (pi * std::pow(n_h * n_h * (a2 - 1) + 1, 2));
    const Dir l_mirrored{l.x, l.y, -l.z};
    const double v_t = heaviside(dot(h, l_mirrored)) / (std::fabs(n_l) + std::sqrt(a2 + (1 - a2) * n_l * n_l)) *
                       heaviside(dot(h, v)) / (std::fabs(n_v) + std::sqrt(a2 + (1 - a2) * n_v * n_v));
    const double fresnel_max = dielectric_fresnel(p, p.specular_color_max, std::pow(1 - std::fabs(dot(v, h)), 5));
    return (1 - p.metallic) * transmission * (1 - fresnel_max) * p.base * v_t * d_t;
}

// KHR_materials_transmission through a KHR_materials_volume interface of
// roughness > 0 as Walter, Marschner, Li and Torrance 2007 write the
// microfacet BTDF (their eqs. 16, 21, 33 and 34), for V above and L below
// the surface (N = +z), V outside the volume (index 1, L inside at index
// ior) or inside (V at ior, L outside):
//   (1 − metallic) · transmission · base · (1 − F_max) ·
//   |L·H| |V·H| / (|L·N| |V·N|) · η_V² G(V, L, H) D(H) / (η_L (L·H) + η_V (V·H))²,
// H = −(η_L L + η_V V) normalised and turned to N's side, D = α² χ⁺(H·N) /
// (π cos⁴θ_H (α² + tan²θ_H)²), G = G1(V) G1(L), G1(X) = χ⁺((X·H)/(X·N)) ·
// 2 / (1 + √(1 + α² tan²θ_X)). F is the layer's Schlick term (with
// KHR_materials_specular's max) at the angle between H and whichever of V
// and L lies outside the volume: the same on both sides of the facet.
inline double rough_refraction(const Params& p, double transmission, bool v_outside, Dir v, Dir l) {
    if (v.z <= 0 || l.z >= 0) return 0;
    constexpr double pi = std::numbers::pi;
    const double a = p.roughness * p.roughness, a2 = a * a;
    const double eta_v = v_outside ? 1 : p.ior, eta_l = v_outside ? p.ior : 1;
    Dir h{-(eta_l * l.x + eta_v * v.x), -(eta_l * l.y + eta_v * v.y), -(eta_l * l.z + eta_v * v.z)};
    const double len = std::sqrt(dot(h, h)) * (h.z < 0 ? -1 : 1);
    h = {h.x / len, h.y / len, h.z / len};
    const auto tan2 = [](double cos_theta) { return (1 - cos_theta * cos_theta) / (cos_theta * cos_theta); };
    const double d_term = a2 * heaviside(h.z) / (pi * std::pow(h.z, 4) * std::pow(a2 + tan2(h.z), 2));
    const auto g1 = [&](Dir x) { return heaviside(dot(x, h) / x.z) * 2 / (1 + std::sqrt(1 + a2 * tan2(x.z))); };
    const double l_h = dot(l, h), v_h = dot(v, h);
    const double jacobian_like = std::fabs(l_h) * std::fabs(v_h) / (std::fabs(l.z) * std::fabs(v.z));
    const double btdf = jacobian_like * eta_v * eta_v * g1(v) * g1(l) * d_term / std::pow(eta_l * l_h + eta_v * v_h, 2);
    const double cos_outer = std::fabs(v_outside ? v_h : l_h);
    const double fresnel_max = dielectric_fresnel(p, p.specular_color_max, std::pow(1 - cos_outer, 5));
    return (1 - p.metallic) * transmission * (1 - fresnel_max) * p.base * btdf;
}

// KHR_materials_clearcoat over the material `base` (its f(V, L), 1/sr) for
// V and L above the surface (N = +z): fresnel_coat(ior 1.5, weight
// clearcoat, base, specular_brdf(α = coat_roughness²)) =
// mix(base, layer, clearcoat · F(0.04, |N·V|)), the layer Appendix B's
// specular_brdf without Fresnel. coat_roughness 0: the delta mirror is left
// out (its weight is clearcoat · F).
inline double coated(double base, double clearcoat, double coat_roughness, Dir v, Dir l) {
    if (v.z <= 0 || l.z <= 0) return 0;
    constexpr double pi = std::numbers::pi;
    const double blend = clearcoat * (0.04 + 0.96 * std::pow(1 - std::fabs(v.z), 5));
    double layer = 0;
    if (coat_roughness > 0) {
        const double a = coat_roughness * coat_roughness, a2 = a * a;
        Dir h{v.x + l.x, v.y + l.y, v.z + l.z};
        const double len = std::sqrt(dot(h, h));
        h = {h.x / len, h.y / len, h.z / len};
        const double d_term = a2 * heaviside(h.z) / (pi * std::pow(h.z * h.z * (a2 - 1) + 1, 2));
        const double vis =
            heaviside(dot(l, h)) * heaviside(dot(v, h)) /
            (2 * (v.z * std::sqrt(a2 + (1 - a2) * l.z * l.z) + l.z * std::sqrt(a2 + (1 - a2) * v.z * v.z)));
        layer = vis * d_term;
    }
    return (1 - blend) * base + blend * layer;
}

// KHR_materials_sheen's lobe, sheen_brdf = D_Charlie · sheen_visibility, for
// V and L above the surface (N = +z), written from the extension's
// implementation notes line by line: alpha_g = r², l(x), lambda_sheen. The
// sheen colour multiplies it. r must be > 0.
inline double sheen_lobe(Dir v, Dir l, double r) {
    if (v.z <= 0 || l.z <= 0) return 0;
    constexpr double pi = std::numbers::pi;
    const double alpha_g = r * r, inv_r = 1 / alpha_g;
    Dir h{v.x + l.x, v.y + l.y, v.z + l.z};
    const double n_h = h.z / std::sqrt(dot(h, h));
    const double distribution = (2 + inv_r) * std::pow(1 - n_h * n_h, inv_r * 0.5) / (2 * pi);
    const double w = (1 - alpha_g) * (1 - alpha_g);
    const auto mix = [w](double x, double y) { return x * (1 - w) + y * w; };
    const auto fit = [&mix](double x) {
        return mix(21.5473, 25.3245) / (1 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
               mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
    };
    const auto lambda = [&fit](double c) {
        return std::fabs(c) < 0.5 ? std::exp(fit(c)) : std::exp(2 * fit(0.5) - fit(1 - c));
    };
    return distribution / ((1 + lambda(v.z) + lambda(l.z)) * (4 * v.z * l.z));
}

// The directional albedo ∫ f(V, L) cos θ_L dL for V at theta_o (radians, in
// the xz plane), by the midpoint rule over half vectors H (θ_h, φ) on an
// n × 2n grid: dL = 4 (V·H) dH, so sharp lobes are resolved by a fine θ_h
// grid. Roughness 0 adds the smooth mirror's Fresnel at cos θ_o to the
// diffuse part's integral.
inline double albedo(const Params& p, double theta_o, int n) {
    constexpr double pi = std::numbers::pi;
    const Dir v{std::sin(theta_o), 0, std::cos(theta_o)};
    const double d_theta = 0.5 * pi / n, d_phi = pi / n;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double th = (i + 0.5) * d_theta, st = std::sin(th), ct = std::cos(th);
        for (int j = 0; j < 2 * n; ++j) {
            const double ph = (j + 0.5) * d_phi;
            const Dir h{st * std::cos(ph), st * std::sin(ph), ct};
            const double v_h = dot(v, h);
            if (v_h <= 0) continue;
            const Dir l{2 * v_h * h.x - v.x, 2 * v_h * h.y - v.y, 2 * v_h * h.z - v.z};
            if (l.z <= 0) continue;
            const double f = p.roughness > 0 ? brdf(p, v, l) : diffuse_part(p, v, l);
            sum += f * l.z * 4 * v_h * st;
        }
    }
    sum *= d_theta * d_phi;
    if (p.roughness > 0) return sum;
    const double w = std::pow(1 - v.z, 5);
    return sum + (1 - p.metallic) * dielectric_fresnel(p, p.specular_color, w) +
           p.metallic * (p.base + (1 - p.base) * w);
}

// albedo at resolution n and its error estimate, |albedo(n) − albedo(n/2)|
// (the midpoint rule's error falls by 4× per doubling, so this bounds it).
struct Quadrature {
    double value, error;
};
inline Quadrature albedo_with_error(const Params& p, double theta_o, int n) {
    const double fine = albedo(p, theta_o, n), coarse = albedo(p, theta_o, n / 2);
    return {fine, std::fabs(fine - coarse)};
}

}  // namespace sombra::pbr_reference
