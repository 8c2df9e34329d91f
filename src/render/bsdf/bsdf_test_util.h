// What the pbr BSDF tests share (bsdf_pbr_test.cpp and the layers' tests):
// directions by angle or from fixed-seed hashes, the flat shading point,
// and a pbr material's parameters for one colour channel as the independent
// reference (render/bsdf/pbr_test_util.h) takes them. Tests only.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "render/bsdf/bsdf.h"
#include "render/bsdf/pbr_test_util.h"
#include "render/sampler.h"
#include "scene/material.h"

namespace sombra::bsdf_testing {

// A unit direction at polar angle theta (degrees) from +z, azimuth phi (radians).
inline Vec3 polar(double theta_deg, double phi) {
    const double t = theta_deg * std::numbers::pi / 180.0;
    return {static_cast<float>(std::sin(t) * std::cos(phi)), static_cast<float>(std::sin(t) * std::sin(phi)),
            static_cast<float>(std::cos(t))};
}

inline float rnd(std::uint32_t i, std::uint64_t key) { return hash_to_unit(i, key); }

// A unit direction uniformly over the hemisphere above +z (n_g's side).
inline Vec3 random_upper(std::uint32_t i, std::uint64_t key) {
    const float z = rnd(2 * i, key), phi = 2.0f * std::numbers::pi_v<float> * rnd(2 * i + 1, key);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// A unit direction uniformly over the sphere.
inline Vec3 random_sphere(std::uint32_t i, std::uint64_t key) {
    const float z = 2.0f * rnd(2 * i, key) - 1.0f, phi = 2.0f * std::numbers::pi_v<float> * rnd(2 * i + 1, key);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

inline pbr_reference::Dir to_dir(Vec3 v) { return {v.x, v.y, v.z}; }

// The shading point with n_s = n_g = +z, seen from outside.
inline const BsdfPoint kFlat = make_bsdf_point({0, 0, 1}, {0, 0, 1}, true);

// Material m's parameters for colour channel `channel`, as the reference takes them.
inline pbr_reference::Params params(const Material& m, int channel) {
    return {m.base_color[channel],          m.metallic, m.roughness, m.ior, m.specular, m.specular_color[channel],
            max_component(m.specular_color)};
}

}  // namespace sombra::bsdf_testing
