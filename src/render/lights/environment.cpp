#include "render/lights/environment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace sombra {

namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr double kPiD = 3.14159265358979323846;

// World to map frame, R_y(−θ)·d, and back, R_y(θ)·m; R_y(α) maps
// (x, z) to (cos α·x + sin α·z, −sin α·x + cos α·z).
Vec3 world_to_map(const Environment& env, Vec3 d) {
    const float c = env.cos_rotate, s = env.sin_rotate;
    return {c * d.x - s * d.z, d.y, s * d.x + c * d.z};
}
Vec3 map_to_world(const Environment& env, Vec3 m) {
    const float c = env.cos_rotate, s = env.sin_rotate;
    return {c * m.x + s * m.z, m.y, -s * m.x + c * m.z};
}

struct MapUV {
    float u, v;
};
// (u, v) of spec §10 for a unit map-frame direction.
MapUV map_uv(Vec3 m) {
    const float u = 0.5f + std::atan2(m.x, -m.z) / (2.0f * kPi);
    const float v = std::acos(std::clamp(m.y, -1.0f, 1.0f)) / kPi;
    return {std::clamp(u, 0.0f, 1.0f), std::clamp(v, 0.0f, 1.0f)};
}

Vec3 texel(const HdrImage& image, int i, int j) {
    const float* p = &image.rgb[3 * (static_cast<std::size_t>(j) * image.width + i)];
    return {p[0], p[1], p[2]};
}

int wrap(int i, int n) {
    i %= n;
    return i < 0 ? i + n : i;
}

// Bilinear lookup, texel centres at ((i + ½)/W, (j + ½)/H), wrapping in u,
// clamped in v.
Vec3 bilinear(const HdrImage& image, float u, float v) {
    const float x = u * static_cast<float>(image.width) - 0.5f;
    const float y = v * static_cast<float>(image.height) - 0.5f;
    const float x0 = std::floor(x), y0 = std::floor(y);
    const float fx = x - x0, fy = y - y0;
    const int i0 = wrap(static_cast<int>(x0), image.width), i1 = wrap(static_cast<int>(x0) + 1, image.width);
    const int j0 = std::clamp(static_cast<int>(y0), 0, image.height - 1);
    const int j1 = std::clamp(static_cast<int>(y0) + 1, 0, image.height - 1);
    const Vec3 top = (1.0f - fx) * texel(image, i0, j0) + fx * texel(image, i1, j0);
    const Vec3 bottom = (1.0f - fx) * texel(image, i0, j1) + fx * texel(image, i1, j1);
    return (1.0f - fy) * top + fy * bottom;
}

// The sampling weights described on Environment::distribution.
std::vector<float> sampling_weights(const HdrImage& image) {
    const int w = image.width, h = image.height;
    std::vector<float> lum(static_cast<std::size_t>(w) * h);
    std::vector<char> positive(lum.size());
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const Vec3 c = texel(image, i, j);
            lum[static_cast<std::size_t>(j) * w + i] = luminance(c);
            positive[static_cast<std::size_t>(j) * w + i] = max_component(c) > 0.0f;
        }
    std::vector<float> weights(lum.size());
    std::vector<char> reachable(lum.size());  // some texel in the 3×3 neighbourhood has radiance
    float largest = 0;
    for (int j = 0; j < h; ++j) {
        const float sin_theta = static_cast<float>(std::sin(kPiD * (j + 0.5) / h));
        for (int i = 0; i < w; ++i) {
            float m = 0;
            bool any = false;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const auto k = static_cast<std::size_t>(std::clamp(j + dj, 0, h - 1)) * w + wrap(i + di, w);
                    m = std::max(m, lum[k]);
                    any = any || positive[k];
                }
            const auto k = static_cast<std::size_t>(j) * w + i;
            weights[k] = m * sin_theta;
            reachable[k] = any;
            largest = std::max(largest, weights[k]);
        }
    }
    // The floor keeps every reachable texel's bin wide enough to be sampled.
    const float floor = std::max(largest * 1e-6f, std::numeric_limits<float>::min());
    for (std::size_t k = 0; k < weights.size(); ++k)
        if (reachable[k]) weights[k] = std::max(weights[k], floor);
    return weights;
}

}  // namespace

Environment make_constant_environment(Vec3 radiance) {
    Environment env;
    env.constant = radiance;
    return env;
}

Environment make_map_environment(HdrImage image, float scale, float rotate_y_degrees) {
    Environment env;
    env.image = std::move(image);
    env.scale = scale;
    env.rotate_y_degrees = rotate_y_degrees;
    const double radians = static_cast<double>(rotate_y_degrees) * kPiD / 180.0;
    env.cos_rotate = static_cast<float>(std::cos(radians));
    env.sin_rotate = static_cast<float>(std::sin(radians));
    if (has_map(env))
        env.distribution = make_distribution_2d(sampling_weights(env.image), env.image.width, env.image.height);
    return env;
}

bool has_map(const Environment& env) { return env.image.width > 0; }

bool is_black(const Environment& env) {
    if (!has_map(env)) return !(max_component(env.constant) > 0.0f);
    return !(env.scale > 0.0f) || env.distribution.marginal.integral == 0.0f;
}

Vec3 eval_environment(const Environment& env, Vec3 direction) {
    if (!has_map(env)) return env.constant;
    const MapUV uv = map_uv(world_to_map(env, direction));
    return env.scale * bilinear(env.image, uv.u, uv.v);
}

float pdf_environment(const Environment& env, Vec3 direction) {
    if (is_black(env)) return 0.0f;
    if (!has_map(env)) return 1.0f / (4.0f * kPi);
    const Vec3 m = world_to_map(env, direction);
    const float sin_theta = std::sqrt(m.x * m.x + m.z * m.z);
    if (!(sin_theta > 0.0f)) return 0.0f;
    const MapUV uv = map_uv(m);
    const float p = pdf(env.distribution, uv.u, uv.v) / (2.0f * kPi * kPi * sin_theta);
    return std::isfinite(p) ? p : 0.0f;
}

bool sample_environment(const Environment& env, float u1, float u2, EnvironmentSample& out) {
    if (is_black(env)) return false;
    if (!has_map(env)) {  // uniform over the sphere
        const float z = 1.0f - 2.0f * u1;
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 2.0f * kPi * u2;
        out.direction = {r * std::cos(phi), r * std::sin(phi), z};
        out.radiance = env.constant;
        out.pdf = 1.0f / (4.0f * kPi);
        return true;
    }
    const Sample2D s = sample(env.distribution, u1, u2);
    if (!(s.pdf > 0.0f)) return false;
    const float theta = s.v * kPi, phi = 2.0f * kPi * (s.u - 0.5f);  // phi = atan2(m.x, −m.z)
    const float sin_theta = std::sin(theta);
    const Vec3 m{sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
    out.direction = map_to_world(env, m);
    // Both from the direction, so that they equal what eval and pdf say of it.
    out.pdf = pdf_environment(env, out.direction);
    if (!(out.pdf > 0.0f)) return false;
    out.radiance = eval_environment(env, out.direction);
    return true;
}

float environment_power_proxy(const Environment& env) {
    if (is_black(env)) return 0.0f;
    if (!has_map(env)) return 4.0f * kPi * luminance(env.constant);
    const int w = env.image.width, h = env.image.height;
    double sum = 0;
    for (int j = 0; j < h; ++j) {
        // The solid angle of a texel in row j: (2π/W)·(cos θ_top − cos θ_bottom).
        const double solid_angle = 2.0 * kPiD / w * (std::cos(kPiD * j / h) - std::cos(kPiD * (j + 1) / h));
        double row = 0;
        for (int i = 0; i < w; ++i) row += luminance(texel(env.image, i, j));
        sum += row * solid_angle;
    }
    return static_cast<float>(sum * env.scale);
}

}  // namespace sombra
