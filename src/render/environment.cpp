#include "render/environment.h"

#include <cmath>
#include <numbers>

namespace sombra {

bool sample_environment(const Environment& env, float u1, float u2, EnvironmentSample& out) {
    // Uniform over the sphere.
    const float z = 1.0f - 2.0f * u1;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * std::numbers::pi_v<float> * u2;
    out.direction = Vec3{r * std::cos(phi), r * std::sin(phi), z};
    out.radiance = env.constant;
    out.pdf = 0.25f * std::numbers::inv_pi_v<float>;
    return true;
}

float pdf_environment(const Environment&, Vec3) { return 0.25f * std::numbers::inv_pi_v<float>; }

float environment_power_proxy(const Environment& env) {
    const Vec3 c = env.constant;
    return 4.0f * std::numbers::pi_v<float> * (0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z);
}

}  // namespace sombra
