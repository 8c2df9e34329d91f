// The Charlie sheen lobe and its albedo table (render/bsdf/sheen.h states the
// formulas and where they come from).
#include "render/bsdf/sheen.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace sombra {
namespace {

// The lobe's arithmetic once, for the float lobe the renderer evaluates and
// the double integral that fills the albedo table, so that the table is the
// albedo of exactly this lobe.
template <typename T>
T charlie_d(T sin2_h, T alpha) {
    const T inv_alpha = T(1) / alpha;
    return (T(2) + inv_alpha) * std::pow(sin2_h, T(0.5) * inv_alpha) / (T(2) * std::numbers::pi_v<T>);
}

// The fitted exponent L(x) of Λ; a…e move from the paper's α = 1 fit to its
// α = 0 fit as (1 − α)² goes from 0 to 1.
template <typename T>
T charlie_l(T x, T alpha) {
    const T t = (T(1) - alpha) * (T(1) - alpha);
    const auto mix = [t](T at_one, T at_zero) { return at_one + (at_zero - at_one) * t; };
    const T a = mix(T(21.5473), T(25.3245));
    const T b = mix(T(3.82987), T(3.32435));
    const T c = mix(T(0.19823), T(0.16801));
    const T d = mix(T(-1.97760), T(-1.27393));
    const T e = mix(T(-4.32054), T(-4.85967));
    return a / (T(1) + b * std::pow(x, c)) + d * x + e;
}

// Λ(cos θ) for cos θ in (0, 1]: the fit is made for grazing angles and
// mirrored about ½ for the others, as the paper does, so that it stays
// smooth and tends to 0 toward the normal.
template <typename T>
T charlie_lambda(T cos_theta, T alpha) {
    if (cos_theta < T(0.5)) return std::exp(charlie_l(cos_theta, alpha));
    return std::exp(T(2) * charlie_l(T(0.5), alpha) - charlie_l(T(1) - cos_theta, alpha));
}

template <typename T>
T charlie_v(T cos_o, T cos_i, T alpha) {
    return T(1) / ((T(1) + charlie_lambda(cos_o, alpha) + charlie_lambda(cos_i, alpha)) * (T(4) * cos_o * cos_i));
}

template <typename T>
T sheen_alpha(T roughness) {
    const T r = std::clamp(roughness, T(kMinSheenRoughness), T(1));
    return r * r;
}

// The table's quadrature: 32 × 16 nodes agree with 2000 × 1000 to 10⁻³
// (far below the bilinear lookup's own error) and build the table in ~30 ms.
constexpr int kTableNodesT = 32, kTableNodesPhi = 16;

const SheenAlbedoTable& albedo_table() {
    // Built once on first use (a sheen material's first evaluation) and
    // read-only after: a function of nothing, as a constant table would be.
    static const SheenAlbedoTable table = make_sheen_albedo_table();
    return table;
}

}  // namespace

float eval_sheen_lobe(Vec3 wo, Vec3 wi, float roughness) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    const float alpha = sheen_alpha(roughness);
    const Vec3 h = normalize(wo + wi);
    // sin²θ_h from the horizontal part: 1 − h.z² cancels near the normal.
    const float sin2_h = h.x * h.x + h.y * h.y;
    return charlie_d(sin2_h, alpha) * charlie_v(wo.z, wi.z, alpha);
}

double sheen_albedo_integral(double mu, double roughness, int nt, int nphi) {
    const double alpha = sheen_alpha(roughness);
    const double v_x = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    const double lambda_o = charlie_lambda(mu, alpha);
    const double dphi = std::numbers::pi / nphi;
    std::vector<double> cos_phi(static_cast<std::size_t>(nphi)), sin_phi(cos_phi.size());
    for (std::size_t q = 0; q < cos_phi.size(); ++q) {
        cos_phi[q] = std::cos((double(q) + 0.5) * dphi);
        sin_phi[q] = std::sin((double(q) + 0.5) * dphi);
    }
    double sum = 0.0;
    for (int k = 0; k < nt; ++k) {
        const double t = (k + 0.5) / nt;
        const double z = t * t, dz = 2.0 * t / nt;
        const double sin_l = std::sqrt(std::max(0.0, 1.0 - z * z));
        // V·cos θ_i·dωi, the same for every φ at this θ_i.
        const double weight = z * dz * dphi / ((1.0 + lambda_o + charlie_lambda(z, alpha)) * (4.0 * mu * z));
        // h = ωo + ωi unnormalised: its horizontal part over its length gives sin²θ_h.
        const double h_z = mu + z;
        for (std::size_t q = 0; q < cos_phi.size(); ++q) {
            const double h_x = v_x + sin_l * cos_phi[q], h_y = sin_l * sin_phi[q];
            const double horizontal = h_x * h_x + h_y * h_y;
            sum += charlie_d(horizontal / (horizontal + h_z * h_z), alpha) * weight;
        }
    }
    return 2.0 * sum;  // φ over [0, π] is half the circle
}

SheenAlbedoTable make_sheen_albedo_table() {
    SheenAlbedoTable table{};
    constexpr int n = kSheenTableSize;
    for (int j = 0; j < n; ++j) {
        const double r = j == 0 ? kMinSheenRoughness : double(j) / (n - 1);
        for (int i = 0; i < n; ++i) {
            // μ = 0 itself has V's 1/cos θ_o against Λ's finite limit there;
            // E is 0 in the limit and ~10⁻⁴ at 10⁻³.
            const double mu = i == 0 ? 1e-3 : double(i) / (n - 1);
            table.e[j][i] = static_cast<float>(sheen_albedo_integral(mu, r, kTableNodesT, kTableNodesPhi));
        }
    }
    return table;
}

float sheen_albedo(float cos_theta, float roughness) {
    constexpr int last = kSheenTableSize - 1;
    constexpr auto span = static_cast<float>(last);
    const float x = std::clamp(cos_theta, 0.0f, 1.0f) * span;
    const float y = std::clamp(roughness, 0.0f, 1.0f) * span;
    const int i = std::min(static_cast<int>(x), last - 1), j = std::min(static_cast<int>(y), last - 1);
    const float fx = x - static_cast<float>(i), fy = y - static_cast<float>(j);
    const SheenAlbedoTable& t = albedo_table();
    const float lo = t.e[j][i] + (t.e[j][i + 1] - t.e[j][i]) * fx;
    const float hi = t.e[j + 1][i] + (t.e[j + 1][i + 1] - t.e[j + 1][i]) * fx;
    return lo + (hi - lo) * fy;
}

}  // namespace sombra
