#include "render/media/homogeneous_medium.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sombra {

namespace {

// exp(−σ·d) for one channel, with 0·∞ read as 0 (no extinction, any distance).
float channel_transmittance(float sigma, float distance) { return sigma > 0.0f ? std::exp(-sigma * distance) : 1.0f; }

float component(Vec3 v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }

}  // namespace

Vec3 homogeneous_transmittance(const Medium& medium, float distance) {
    const Vec3 sigma_t = extinction(medium);
    return {channel_transmittance(sigma_t.x, distance), channel_transmittance(sigma_t.y, distance),
            channel_transmittance(sigma_t.z, distance)};
}

Vec3 homogeneous_emission(const Medium& medium, float distance) {
    const Vec3 sigma_t = extinction(medium);
    const auto emitted = [distance](float epsilon, float sigma) {
        if (!(epsilon > 0.0f)) return 0.0f;
        // −expm1(−σd)/σ keeps its precision for a thin medium (σd ≪ 1).
        return sigma > 0.0f ? epsilon * static_cast<float>(-std::expm1(-static_cast<double>(sigma) * distance) / sigma)
                            : epsilon * distance;
    };
    return {emitted(medium.emission.x, sigma_t.x), emitted(medium.emission.y, sigma_t.y),
            emitted(medium.emission.z, sigma_t.z)};
}

FreeFlight sample_homogeneous_free_flight(const Medium& medium, float end, float u_channel, float u_distance) {
    const Vec3 sigma_t = extinction(medium);
    const int channel = std::min(static_cast<int>(u_channel * 3.0f), 2);
    const float sigma = component(sigma_t, channel);
    // −log(1 − u)/σ: finite for u < 1 and σ > 0; a channel without extinction never interacts.
    const float t = sigma > 0.0f ? static_cast<float>(-std::log1p(-static_cast<double>(u_distance)) / sigma)
                                 : std::numeric_limits<float>::infinity();
    FreeFlight f;
    if (t < end) {
        const Vec3 transmittance = homogeneous_transmittance(medium, t);
        // p(t) = (1/3) Σ_c σ_c exp(−σ_c t): the density of t over the channel's choice.
        const float pdf =
            (sigma_t.x * transmittance.x + sigma_t.y * transmittance.y + sigma_t.z * transmittance.z) / 3.0f;
        f.scattered = true;
        f.t = t;
        f.weight = pdf > 0.0f ? transmittance * medium.sigma_s / pdf : Vec3{0.0f};
        return f;
    }
    const Vec3 transmittance = homogeneous_transmittance(medium, end);
    // P(t ≥ end) = (1/3) Σ_c exp(−σ_c end); it is > 0 here, since t ≥ end happened.
    const float reach = (transmittance.x + transmittance.y + transmittance.z) / 3.0f;
    f.weight = reach > 0.0f ? transmittance / reach : Vec3{0.0f};
    return f;
}

}  // namespace sombra
