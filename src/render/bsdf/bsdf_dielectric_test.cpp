// Tests of the smooth dielectric (render/bsdf/bsdf.h): Fresnel against the
// polarised formulas in double, Snell's law, total internal reflection, the
// radiance-transport weight, from both sides of the surface.
#include <gtest/gtest.h>

#include <cmath>

#include "render/bsdf/bsdf.h"
#include "render/sampler.h"

namespace sombra {
namespace {

constexpr double kPi = 3.14159265358979323846;

Material glass(float ior, Vec3 kt) {
    Material m{"g", MaterialType::Dielectric, {}, {}, 1, {}};
    m.ior = ior;
    m.kt = kt;
    return m;
}

// Fresnel from the angles: R_s = sin²(θi−θt)/sin²(θi+θt), R_p = tan²(θi−θt)/tan²(θi+θt).
double fresnel_reference(double theta_i, double eta_i, double eta_t) {
    const double s = eta_i / eta_t * std::sin(theta_i);
    if (s >= 1) return 1;
    if (theta_i == 0) return std::pow((eta_i - eta_t) / (eta_i + eta_t), 2);
    const double theta_t = std::asin(s);
    const double rs = std::pow(std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t), 2);
    const double rp = std::pow(std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t), 2);
    return 0.5 * (rs + rp);
}

Vec3 polar(double theta_deg) {
    const double t = theta_deg * kPi / 180.0;
    return {static_cast<float>(std::sin(t)), 0.0f, static_cast<float>(std::cos(t))};
}

TEST(BsdfDielectric, ReflectionProbabilityIsFresnelAndRefractionObeysSnell) {
    const Material m = glass(1.5f, {0.9f, 0.8f, 0.7f});
    for (const bool outside : {true, false}) {
        const BsdfPoint p = make_bsdf_point({0, 0, 1}, {0, 0, 1}, outside);
        const double eta_i = outside ? 1.0 : 1.5, eta_t = outside ? 1.5 : 1.0;
        for (const double theta : {0.0, 10.0, 30.0, 40.0, 41.0, 60.0, 85.0}) {
            const Vec3 wo = polar(theta);
            const double F = fresnel_reference(theta * kPi / 180, eta_i, eta_t);
            EXPECT_NEAR(fresnel_dielectric(wo.z, static_cast<float>(eta_i), static_cast<float>(eta_t)), F, 2e-6);
            const int n = 20000;
            int reflected = 0;
            for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(n); ++i) {
                BsdfSample s;
                ASSERT_TRUE(sample_bsdf(m, p, wo, hash_to_unit(i, 77), 0.5f, 0.5f, s));
                ASSERT_TRUE(s.delta);
                if (!s.transmission) {
                    ++reflected;
                    EXPECT_EQ(s.weight, Vec3{1.0f});
                    EXPECT_NEAR(s.pdf, F, 2e-6);
                    EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
                    EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
                } else {
                    EXPECT_NEAR(s.pdf, 1 - F, 2e-6);
                    const double r = eta_i / eta_t;
                    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], m.kt[c] * r * r, 1e-5);
                    // Snell: η_i sin θ_i = η_t sin θ_t, on the other side, in the plane of incidence.
                    EXPECT_LT(s.wi.z, 0.0f);
                    EXPECT_NEAR(eta_t * std::hypot(s.wi.x, s.wi.y), eta_i * std::sin(theta * kPi / 180), 1e-5);
                    EXPECT_LE(s.wi.x * wo.x, 0.0f);
                    EXPECT_NEAR(s.wi.y, 0.0f, 1e-6f);
                }
            }
            // Binomial z-test of the reflection frequency.
            if (F > 0 && F < 1) {
                EXPECT_LT(std::fabs(reflected - n * F) / std::sqrt(n * F * (1 - F)), 4.0) << theta;
            }
            if (F == 1) {
                EXPECT_EQ(reflected, n) << "total internal reflection at " << theta << "°";
            }
        }
    }
    // From inside, beyond the critical angle asin(1/1.5) = 41.8°: always reflected.
    EXPECT_EQ(fresnel_dielectric(polar(42).z, 1.5f, 1.0f), 1.0f);
    EXPECT_LT(fresnel_dielectric(polar(41.5).z, 1.5f, 1.0f), 1.0f);
}

TEST(BsdfDielectric, ASlabTransmitsKtSquaredAlongTheIncidentDirection) {
    const Material m = glass(1.7f, {0.9f, 0.6f, 0.3f});
    for (const double theta : {0.0, 25.0, 70.0}) {
        const Vec3 wo = polar(theta);
        BsdfSample in, out;
        // Enter from outside through the top face (normal +z), u_lobe near 1: refraction.
        ASSERT_TRUE(sample_bsdf(m, make_bsdf_point({0, 0, 1}, {0, 0, 1}, true), wo, 0x1.fffffep-1f, 0, 0, in));
        ASSERT_TRUE(in.transmission);
        // Leave through the parallel bottom face from inside: its normals face the ray's origin (+z).
        ASSERT_TRUE(sample_bsdf(m, make_bsdf_point({0, 0, 1}, {0, 0, 1}, false), -in.wi, 0x1.fffffep-1f, 0, 0, out));
        ASSERT_TRUE(out.transmission);
        const Vec3 throughput = in.weight * out.weight;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(throughput[c], m.kt[c] * m.kt[c], 1e-5f);
        EXPECT_NEAR(out.wi.x, -wo.x, 1e-5f);
        EXPECT_NEAR(out.wi.z, -wo.z, 1e-5f);
        // Both faces see the same Fresnel reflectance (reciprocity), so pdfs match.
        EXPECT_NEAR(in.pdf, out.pdf, 1e-5f);
    }
}

TEST(BsdfDielectric, IsDeltaAndNeverLeaksThroughTheGeometricNormal) {
    const Material m = glass(1.5f, Vec3{1.0f});
    EXPECT_TRUE(is_delta_bsdf(m));
    // A shading normal tilted 40° about y: near-grazing refraction can land on n_g's side.
    const float c = static_cast<float>(std::cos(40 * kPi / 180)), s = static_cast<float>(std::sin(40 * kPi / 180));
    const BsdfPoint p = make_bsdf_point({0, 0, 1}, {s, 0, c}, true);
    for (std::uint32_t i = 0; i < 2000; ++i) {
        const Vec3 wo = polar(-89.0 + 178.0 * hash_to_unit(i, 5));
        EXPECT_EQ(eval_bsdf(m, p, wo, Vec3{0, 0, -1}), Vec3{0.0f});
        EXPECT_EQ(pdf_bsdf(m, p, wo, Vec3{0, 0, -1}), 0.0f);
        BsdfSample b;
        if (!sample_bsdf(m, p, wo, hash_to_unit(i, 6), 0, 0, b)) continue;
        ASSERT_TRUE(is_finite(b.weight));
        if (b.transmission)
            EXPECT_LT(b.wi.z, 0.0f);
        else
            EXPECT_GT(b.wi.z, 0.0f);
    }
}

}  // namespace
}  // namespace sombra
