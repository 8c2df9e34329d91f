#include "render/media/phase_function.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/frame.h"

namespace sombra {

namespace {

constexpr double kInvFourPi = 0.25 * std::numbers::inv_pi;

// Below this |g| the inverse of the distribution divides by almost 0, and
// the isotropic inverse is exact to float precision instead.
constexpr double kIsotropicBelow = 1e-4;

}  // namespace

float henyey_greenstein(float g, float cos_theta) {
    // In double: for |g| near 1 the denominator's 1 + g² − 2g cos θ cancels.
    const double gd = g, c = std::clamp(static_cast<double>(cos_theta), -1.0, 1.0);
    const double denominator = 1.0 + gd * gd - 2.0 * gd * c;
    return static_cast<float>(kInvFourPi * (1.0 - gd * gd) / (denominator * std::sqrt(denominator)));
}

PhaseSample sample_henyey_greenstein(float g, Vec3 in, float u1, float u2) {
    const double gd = g, u = u1;
    double cos_theta;
    if (std::fabs(gd) < kIsotropicBelow) {
        cos_theta = 2.0 * u - 1.0;  // the limit g → 0 of the inverse below
    } else {
        // The inverse of P(cos θ ≤ c): cos θ = (1 + g² − ((1 − g²)/(1 − g + 2gu))²) / (2g).
        const double ratio = (1.0 - gd * gd) / (1.0 - gd + 2.0 * gd * u);
        cos_theta = (1.0 + gd * gd - ratio * ratio) / (2.0 * gd);
    }
    cos_theta = std::clamp(cos_theta, -1.0, 1.0);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = 2.0 * std::numbers::pi * static_cast<double>(u2);
    const Vec3 local{static_cast<float>(sin_theta * std::cos(phi)), static_cast<float>(sin_theta * std::sin(phi)),
                     static_cast<float>(cos_theta)};
    PhaseSample s;
    s.out = normalize(Frame::from_normal(in).to_world(local));
    s.pdf = henyey_greenstein(g, dot(in, s.out));
    return s;
}

}  // namespace sombra
