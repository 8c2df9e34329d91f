#include "render/bsdf/brdf.h"

#include <gtest/gtest.h>

namespace sombra {
namespace {

constexpr double kPi = 3.14159265358979323846;

Material phong(Vec3 kd, Vec3 ks, float n) { return Material{"p", MaterialType::Phong, kd, ks, n, {}}; }

Vec3 direction(double theta, double phi) {
    return {static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::sin(theta) * std::sin(phi)),
            static_cast<float>(std::cos(theta))};
}

TEST(Brdf, LambertIsKdOverPi) {
    const Material m{"d", MaterialType::Diffuse, {0.5f, 0.25f, 1.0f}, {}, 1, {}};
    const Vec3 f = eval_brdf(m, {0, 0, 1}, direction(0.3, 1.0), direction(1.2, -2.0));
    EXPECT_FLOAT_EQ(f.x, 0.5f / static_cast<float>(kPi));
    EXPECT_FLOAT_EQ(f.y, 0.25f / static_cast<float>(kPi));
    EXPECT_FLOAT_EQ(f.z, 1.0f / static_cast<float>(kPi));
}

TEST(Brdf, PhongPeaksInTheMirrorDirection) {
    const Vec3 n{0, 0, 1};
    const Vec3 wi = direction(kPi / 6, 0);        // 30° from the normal
    const Vec3 mirror = direction(kPi / 6, kPi);  // r = 2(n·ωi)n − ωi
    const float shininess = 20;
    const Material m = phong({0.2f, 0.2f, 0.2f}, {0.5f, 0.5f, 0.5f}, shininess);
    const Vec3 f = eval_brdf(m, n, wi, mirror);
    const float expected = 0.2f / static_cast<float>(kPi) + 0.5f * (shininess + 2) / (2 * static_cast<float>(kPi));
    EXPECT_NEAR(f.x, expected, 1e-5f);
}

TEST(Brdf, PhongFallsOffAsCosinePowerOfTheAngleToTheMirror) {
    const Vec3 n{0, 0, 1};
    const Vec3 wi = direction(kPi / 4, 0);
    const double alpha = 0.2;  // ωo is 0.2 rad from the mirror direction (θ = 45° − 0.2 on the far side)
    const Vec3 wo = direction(kPi / 4 - alpha, kPi);
    const float shininess = 10;
    const float lobe = eval_phong_lobe(n, wi, wo, shininess);
    EXPECT_NEAR(lobe, (shininess + 2) / (2 * kPi) * std::pow(std::cos(alpha), shininess), 1e-5);
    // Exactly 90° from the mirror direction (ωo = ωi at 45°) the lobe is 0.
    EXPECT_NEAR(eval_phong_lobe(n, wi, wi, shininess), 0.0f, 1e-6f);
}

TEST(Brdf, PhongLobeIsZeroPastNinetyDegreesAndConstantForNZero) {
    const Vec3 n{0, 0, 1};
    const Vec3 wi = direction(kPi / 3, 0);
    const Vec3 far = direction(kPi / 3, 0);  // r·ωo = cos(120°) < 0
    EXPECT_EQ(eval_phong_lobe(n, wi, far, 5), 0.0f);
    // n = 0: x⁰ = 1, even where r·ωo ≤ 0 (spec §9): a constant 2/(2π).
    EXPECT_NEAR(eval_phong_lobe(n, wi, far, 0), 1 / kPi, 1e-7);
    EXPECT_NEAR(eval_phong_lobe(n, wi, direction(0.1, 2), 0), 1 / kPi, 1e-7);
}

// ∫ f_r(ωi, ωo) cos θi dωi over the hemisphere, by the midpoint rule in (θ, φ).
Vec3 directional_albedo(const Material& m, Vec3 wo, int n_theta, int n_phi) {
    const Vec3 n{0, 0, 1};
    double sum[3] = {0, 0, 0};
    const double d_theta = kPi / 2 / n_theta, d_phi = 2 * kPi / n_phi;
    for (int a = 0; a < n_theta; ++a) {
        const double theta = (a + 0.5) * d_theta;
        const double weight = std::cos(theta) * std::sin(theta) * d_theta * d_phi;
        for (int b = 0; b < n_phi; ++b) {
            const Vec3 f = eval_brdf(m, n, direction(theta, (b + 0.5) * d_phi), wo);
            for (int c = 0; c < 3; ++c) sum[c] += f[c] * weight;
        }
    }
    return {static_cast<float>(sum[0]), static_cast<float>(sum[1]), static_cast<float>(sum[2])};
}

TEST(Brdf, PhongLobeAlbedoIsOneAtNormalIncidence) {
    // With ωo = n the lobe integrates exactly to 1: (n+2)/(2π) ∫ cos^(n+1) θ dω = 1.
    for (float shininess : {0.0f, 1.0f, 10.0f, 60.0f}) {
        const Vec3 a = directional_albedo(phong({0, 0, 0}, {1, 1, 1}, shininess), {0, 0, 1}, 600, 64);
        EXPECT_NEAR(a.x, 1.0f, 2e-3f) << "n = " << shininess;
    }
}

TEST(Brdf, DiffuseAlbedoIsKd) {
    const Material m{"d", MaterialType::Diffuse, {0.7f, 0.7f, 0.7f}, {}, 1, {}};
    EXPECT_NEAR(directional_albedo(m, direction(0.8, 0.3), 400, 64).x, 0.7f, 1e-3f);
}

TEST(Brdf, PhongConservesEnergyWhenKdPlusKsIsAtMostOne) {
    // At grazing ωo part of the lobe falls below the horizon, so the albedo
    // only decreases; it never exceeds kd + ks.
    for (float shininess : {0.0f, 1.0f, 5.0f, 30.0f, 100.0f})
        for (double theta_o : {0.0, 0.5, 1.0, 1.4, 1.55})
            for (float ks : {0.2f, 0.5f, 1.0f}) {
                const Material m = phong(Vec3{1.0f - ks}, Vec3{ks}, shininess);
                const Vec3 a = directional_albedo(m, direction(theta_o, 0.7), 500, 400);
                EXPECT_LE(a.x, 1.0f + 2e-3f) << "n=" << shininess << " θo=" << theta_o << " ks=" << ks;
                EXPECT_GT(a.x, 0.0f);
            }
}

}  // namespace
}  // namespace sombra
