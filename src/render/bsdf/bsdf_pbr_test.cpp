// Tests of spec §11's `pbr` BSDF (render/bsdf/bsdf_pbr.cpp) through render/bsdf/bsdf.h:
// its values against an independent double-precision transcription of the
// glTF 2.0 specification's Appendix B (render/bsdf/pbr_test_util.h), reciprocity,
// no light leaks, χ² fits of sampling against the pdf, and directional
// albedos by Monte Carlo against quadrature (z-tests with the sample
// variance; fixed seeds).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <vector>

#include "render/bsdf/bsdf.h"
#include "render/bsdf/bsdf_test_util.h"
#include "render/bsdf/pbr_test_util.h"
#include "render/chi2_test_util.h"
#include "render/sampler.h"

namespace sombra {
namespace {

namespace ref = pbr_reference;
using bsdf_testing::kFlat;
using bsdf_testing::params;
using bsdf_testing::polar;
using bsdf_testing::random_upper;
using bsdf_testing::rnd;
using bsdf_testing::to_dir;

constexpr double kPi = 3.14159265358979323846;
// |z| beyond this fails: ~1 in 10^6 for a correct estimator.
constexpr double kZ = 5.0;
// Every χ² test in this file, for the Šidák correction of the suite's α = 0.01.
constexpr int kChi2Tests = 5 * 3 * 4 + 3 + 4;

Material pbr(Vec3 base_color, float metallic, float roughness, float ior = 1.5f) {
    Material m;
    m.type = MaterialType::Pbr;
    m.base_color = base_color;
    m.metallic = metallic;
    m.roughness = roughness;
    m.ior = ior;
    return m;
}

// A pbr material with glTF's KHR_materials_specular.
Material with_specular(Material m, float specular, Vec3 specular_color) {
    m.specular = specular;
    m.specular_color = specular_color;
    return m;
}

// A shading normal tilted 25° away from the geometric one.
const BsdfPoint kTilted = make_bsdf_point({0, 0, 1}, polar(25, 1.0), true);

// Rough and smooth materials, dielectric, metal and between.
std::vector<Material> materials() {
    std::vector<Material> out;
    for (const float r : {0.0f, 0.1f, 0.3f, 0.6f, 1.0f})
        for (const float metallic : {0.0f, 0.4f, 1.0f}) out.push_back(pbr({0.9f, 0.5f, 0.1f}, metallic, r));
    out.push_back(pbr({0.2f, 0.7f, 1.0f}, 0.0f, 0.5f, 2.4f));
    out.push_back(pbr(Vec3{0.0f}, 0.0f, 0.3f));
    // KHR_materials_specular: weaker and coloured layers, a colour past 1
    // (clamped to f0 = 1 in one channel), gltf-transform's metalrough output
    // (ior 1000, colour 0.2), and no layer at all.
    out.push_back(with_specular(pbr({0.9f, 0.5f, 0.1f}, 0.0f, 0.4f), 0.5f, {1.0f, 0.2f, 0.6f}));
    out.push_back(with_specular(pbr({0.3f, 0.6f, 0.9f}, 0.3f, 0.0f), 0.8f, {30.0f, 1.0f, 0.0f}));
    out.push_back(with_specular(pbr({0.8f, 0.8f, 0.8f}, 0.0f, 0.6f, 1000.0f), 1.0f, Vec3{0.2f}));
    out.push_back(with_specular(pbr({0.5f, 0.4f, 0.3f}, 0.0f, 0.5f), 0.0f, Vec3{1.0f}));
    return out;
}

TEST(Pbr, EvalMatchesAppendixB) {
    // Float rounding of h moves a lobe of width α by ~ε/α relative (< 1e-4
    // for α ≥ 0.01); 1e-3 keeps a margin yet catches any change of formula
    // (the separable Smith G instead of the height-correlated one, or F at
    // cos θ_o instead of ωo·h, changes f by percents).
    std::uint64_t key = 10;
    for (const Material& m : materials()) {
        ++key;
        for (std::uint32_t i = 0; i < 3000; ++i) {
            const Vec3 wo = random_upper(i, key), wi = random_upper(i, key + 1000);
            const Vec3 f = eval_bsdf(m, kFlat, wo, wi);
            for (int c = 0; c < 3; ++c) {
                const ref::Params p = params(m, c);
                const double expected = m.roughness > 0 ? ref::brdf(p, to_dir(wo), to_dir(wi))
                                                        : ref::diffuse_part(p, to_dir(wo), to_dir(wi));
                ASSERT_NEAR(f[c], expected, 1e-3 * expected + 1e-7)
                    << "r " << m.roughness << " m " << m.metallic << " channel " << c << " wo.z " << wo.z << " wi.z "
                    << wi.z;
            }
        }
    }
}

TEST(Pbr, AtNormalIncidenceAndReflectionTheTermsAreTheClosedForms) {
    // ωi = ωo = n: h = n, D = 1/(πα²), V = 1/(2(1 + 1)) = 1/4, F = f0 (0.04 for ior 1.5) and base_color.
    const Vec3 n{0, 0, 1};
    const Material m = pbr({0.8f, 0.4f, 0.2f}, 0.25f, 0.5f, 1.5f);
    const double alpha = 0.25, d = 1 / (kPi * alpha * alpha), v = 0.25, f0 = 0.04;
    const Vec3 f = eval_bsdf(m, kFlat, n, n);
    for (int c = 0; c < 3; ++c) {
        const double base = m.base_color[c];
        const double expected = 0.75 * ((1 - f0) * base / kPi + f0 * v * d) + 0.25 * base * v * d;
        EXPECT_NEAR(f[c], expected, 1e-5 * expected);
    }
}

TEST(Pbr, EvalIsReciprocal) {
    for (const Material& m : materials()) {
        for (std::uint32_t i = 0; i < 2000; ++i) {
            const Vec3 a = random_upper(i, 31), b = random_upper(i, 32);
            const Vec3 fab = eval_bsdf(m, kTilted, a, b), fba = eval_bsdf(m, kTilted, b, a);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(fab[c], fba[c], 1e-4f * std::max(1.0f, fab[c]));
        }
    }
}

TEST(Pbr, NoLightLeaksThroughTheGeometricNormal) {
    for (const Material& m : materials()) {
        for (std::uint32_t i = 0; i < 2000; ++i) {
            const Vec3 wo = random_upper(i, 61);
            Vec3 below = random_upper(i, 62);
            below.z = -below.z;
            for (const BsdfPoint& p : {kFlat, kTilted}) {
                EXPECT_EQ(eval_bsdf(m, p, wo, below), Vec3{0.0f});
                EXPECT_EQ(pdf_bsdf(m, p, wo, below), 0.0f);
                BsdfSample s;
                if (sample_bsdf(m, p, wo, rnd(3 * i, 63), rnd(3 * i + 1, 63), rnd(3 * i + 2, 63), s)) {
                    EXPECT_GT(dot(p.n_g, s.wi), 0.0f);
                    EXPECT_FALSE(s.transmission);
                }
            }
        }
    }
    // Above the tilted n_s's plane but below n_g's: nothing.
    const Vec3 under = normalize(Vec3{kTilted.n_s.x, kTilted.n_s.y, -0.05f});
    ASSERT_GT(dot(kTilted.n_s, under), 0.0f);
    for (const Material& m : materials()) {
        EXPECT_EQ(eval_bsdf(m, kTilted, polar(20, 0.3), under), Vec3{0.0f});
        EXPECT_EQ(pdf_bsdf(m, kTilted, polar(20, 0.3), under), 0.0f);
    }
}

TEST(Pbr, WeightIsEvalTimesCosOverPdf) {
    for (const Material& m : materials()) {
        for (const BsdfPoint& p : {kFlat, kTilted}) {
            int rough = 0, delta = 0;
            for (std::uint32_t i = 0; i < 4000; ++i) {
                const Vec3 wo = random_upper(i, 21);
                BsdfSample s;
                if (!sample_bsdf(m, p, wo, rnd(3 * i, 22), rnd(3 * i + 1, 22), rnd(3 * i + 2, 22), s)) continue;
                ASSERT_FALSE(s.transmission);
                ASSERT_GT(s.pdf, 0.0f);
                ASSERT_TRUE(is_finite(s.weight));
                EXPECT_NEAR(length(s.wi), 1.0f, 1e-5f);
                if (s.delta) {
                    // The smooth specular part: the mirror direction, chosen with
                    // probability s.pdf, weighted by its Fresnel factor over it.
                    ++delta;
                    ASSERT_LT(m.roughness * m.roughness, kDeltaAlpha);
                    const Vec3 mirror = 2.0f * dot(wo, p.n_s) * p.n_s - wo;
                    EXPECT_NEAR(length(s.wi - mirror), 0.0f, 1e-5f);
                    const float cos_o = dot(wo, p.n_s), w = std::pow(1.0f - cos_o, 5.0f);
                    for (int c = 0; c < 3; ++c) {
                        const double dielectric = ref::dielectric_fresnel(params(m, c), m.specular_color[c], w);
                        const double fresnel =
                            (1 - m.metallic) * dielectric + m.metallic * (m.base_color[c] + (1 - m.base_color[c]) * w);
                        EXPECT_NEAR(s.weight[c] * s.pdf, fresnel, 1e-5f);
                    }
                    continue;
                }
                ++rough;
                EXPECT_EQ(s.pdf, pdf_bsdf(m, p, wo, s.wi));
                const Vec3 expected = eval_bsdf(m, p, wo, s.wi) * (std::fabs(dot(p.n_s, s.wi)) / s.pdf);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], expected[c], 1e-5f * std::max(1e-3f, expected[c]));
            }
            EXPECT_GT(rough + delta, 1000);
            // A smooth metal has only its mirror; everything else samples its lobes.
            if (m.roughness > 0 || m.metallic < 1) {
                EXPECT_GT(rough, 300);
            }
            if (m.roughness == 0) {
                EXPECT_GT(delta, 300);
            }
        }
    }
}

// χ² of sample_bsdf against pdf_bsdf, binned around wo's mirror direction;
// delta samples count as failures, which the test expects in proportion
// 1 − ∫pdf (the mirror's selection probability).
void expect_chi2(const Material& m, const BsdfPoint& p, Vec3 wo, std::uint64_t seed) {
    const Vec3 mirror = normalize(2.0f * dot(wo, p.n_s) * p.n_s - wo);
    const auto sample = [&](std::uint32_t i) -> std::optional<Vec3> {
        BsdfSample s;
        if (!sample_bsdf(m, p, wo, rnd(3 * i, seed), rnd(3 * i + 1, seed), rnd(3 * i + 2, seed), s) || s.delta)
            return std::nullopt;
        return s.wi;
    };
    const auto pdf = [&](Vec3 wi) { return pdf_bsdf(m, p, wo, wi); };
    chi2::Options o;
    o.test_count = kChi2Tests;
    const chi2::Result r = chi2::run(Frame::from_normal(mirror), sample, pdf, o);
    EXPECT_TRUE(r.passed) << "r " << m.roughness << " m " << m.metallic << ": " << r.message;
    if (std::getenv("SOMBRA_CHI2_VERBOSE")) std::printf("%s\n", r.message.c_str());
    const double f = r.success_fraction;
    EXPECT_NEAR(r.pdf_integral, f, 5 * std::sqrt(f * (1 - f) / o.samples) + 2e-3) << r.message;
}

TEST(Pbr, Chi2SamplingMatchesThePdf) {
    std::uint64_t seed = 400;
    for (const float r : {0.0f, 0.1f, 0.3f, 0.6f, 1.0f})
        for (const float metallic : {0.0f, 0.5f, 1.0f})
            for (const double theta : {0.0, 30.0, 60.0, 85.0})
                expect_chi2(pbr({0.9f, 0.6f, 0.3f}, metallic, r), kFlat, polar(theta, -0.7), ++seed);
    // n_s 25° off n_g: part of each lobe is cut off by n_g.
    expect_chi2(pbr({0.5f, 0.5f, 0.5f}, 0.0f, 0.3f), kTilted, polar(40, 2.0), 501);
    expect_chi2(pbr({0.5f, 0.5f, 0.5f}, 0.5f, 0.7f), kTilted, polar(30, 1.0 + kPi), 502);
    expect_chi2(pbr({0.5f, 0.5f, 0.5f}, 0.0f, 0.0f), kTilted, polar(60, 1.0 + kPi), 503);
    // KHR_materials_specular moves weight between the lobes.
    expect_chi2(with_specular(pbr({0.9f, 0.6f, 0.3f}, 0.0f, 0.4f), 0.3f, {1.0f, 0.2f, 0.6f}), kFlat, polar(30, 0.4),
                504);
    expect_chi2(with_specular(pbr({0.9f, 0.6f, 0.3f}, 0.0f, 0.4f), 1.0f, {25.0f, 25.0f, 25.0f}), kFlat, polar(60, 0.4),
                505);
    expect_chi2(with_specular(pbr(Vec3{0.8f}, 0.0f, 0.6f, 1000.0f), 1.0f, Vec3{0.2f}), kFlat, polar(45, 0.4), 506);
    expect_chi2(with_specular(pbr(Vec3{0.8f}, 0.2f, 0.5f), 0.0f, Vec3{1.0f}), kFlat, polar(10, 0.4), 507);
}

TEST(Pbr, SpecularExtensionAtNormalIncidenceIsTheClosedForm) {
    // ωi = ωo = n: F_d = min(0.04 · colour, 1) · specular per channel, and
    // the base keeps 1 − max over channels (KHR_materials_specular's fresnel_mix).
    const Vec3 n{0, 0, 1};
    const Material m = with_specular(pbr({0.8f, 0.4f, 0.2f}, 0.0f, 0.5f, 1.5f), 0.5f, {1.0f, 10.0f, 40.0f});
    const double alpha = 0.25, d = 1 / (kPi * alpha * alpha), v = 0.25;
    const double fd[3] = {0.04 * 0.5, 0.4 * 0.5, 1.0 * 0.5};  // 0.04 · 40 = 1.6 is clamped to 1
    const Vec3 f = eval_bsdf(m, kFlat, n, n);
    for (int c = 0; c < 3; ++c) {
        const double expected = (1 - 0.5) * m.base_color[c] / kPi + fd[c] * v * d;
        EXPECT_NEAR(f[c], expected, 1e-5 * expected) << "channel " << c;
    }
    // specular = 0: no layer, a Lambertian base.
    const Material lambert = with_specular(pbr({0.8f, 0.4f, 0.2f}, 0.0f, 0.5f), 0.0f, Vec3{1.0f});
    const Vec3 wi = polar(50, 2.0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(eval_bsdf(lambert, kFlat, n, wi)[c], lambert.base_color[c] / kPi, 1e-7);
}

// The mean sample weight of channel c (the directional albedo ∫ f cos θ_i dωi
// in expectation, delta samples included) and its standard error.
struct Albedo {
    double mean, error;
};
Albedo albedo(const Material& m, Vec3 wo, int c, std::uint32_t n, std::uint64_t key) {
    double sum = 0, sum2 = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        BsdfSample s;
        if (!sample_bsdf(m, kFlat, wo, rnd(3 * i, key), rnd(3 * i + 1, key), rnd(3 * i + 2, key), s)) continue;
        sum += s.weight[c];
        sum2 += static_cast<double>(s.weight[c]) * s.weight[c];
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1))};
}

TEST(Pbr, AlbedoMatchesQuadratureOfAppendixB) {
    // White furnace: base colour 1 (and a coloured one), every roughness
    // class, dielectric to metal; the sampler's mean weight against an
    // independent quadrature of Appendix B's f·cos θ_i.
    std::uint64_t key = 70;
    for (const float r : {0.0f, 0.3f, 0.6f, 1.0f})
        for (const float metallic : {0.0f, 0.5f, 1.0f})
            for (const Vec3 base : {Vec3{1.0f}, Vec3{0.8f, 0.3f, 0.05f}})
                for (const double theta : {0.0, 45.0, 80.0}) {
                    const Material m = pbr(base, metallic, r);
                    const int c = base.x == base.z ? 0 : 2;
                    const Albedo a = albedo(m, polar(theta, 0.3), c, 20000, ++key);
                    const ref::Quadrature q = ref::albedo_with_error(params(m, c), theta * kPi / 180, 400);
                    // A smooth metal's weights do not vary: then float rounding bounds the difference.
                    const double rounding = 1e-6 * std::max(1.0, q.value);
                    EXPECT_LT(std::fabs(a.mean - q.value), kZ * a.error + q.error + rounding)
                        << "r " << r << " m " << metallic << " at " << theta << "°: " << a.mean << " ± " << a.error
                        << ", quadrature " << q.value << " ± " << q.error;
                }
    // KHR_materials_specular, each channel (the coloured Fresnel and the base's max_value differ by channel).
    for (const float r : {0.0f, 0.4f})
        for (const Material& m : {with_specular(pbr({0.9f, 0.5f, 0.1f}, 0.2f, r), 0.6f, {1.0f, 8.0f, 30.0f}),
                                  with_specular(pbr(Vec3{1.0f}, 0.0f, r, 1000.0f), 1.0f, Vec3{0.2f})})
            for (int c = 0; c < 3; ++c) {
                const Albedo a = albedo(m, polar(50, 0.3), c, 20000, ++key);
                const ref::Quadrature q = ref::albedo_with_error(params(m, c), 50 * kPi / 180, 400);
                EXPECT_LT(std::fabs(a.mean - q.value), kZ * a.error + q.error + 1e-6)
                    << "r " << r << " channel " << c << ": " << a.mean << " ± " << a.error << ", quadrature " << q.value
                    << " ± " << q.error;
            }
}

TEST(Pbr, MetalAlbedoIsAtMostOne) {
    // A white metal (base colour 1, so F = 1) with single scattering loses
    // what its microfacets shadow, and never gains.
    std::uint64_t key = 90;
    for (const float r : {0.0f, 0.1f, 0.3f, 0.6f, 1.0f})
        for (const double theta : {0.0, 30.0, 60.0, 85.0}) {
            const Albedo a = albedo(pbr(Vec3{1.0f}, 1.0f, r), polar(theta, 0.3), 0, 20000, ++key);
            EXPECT_LE(a.mean, 1.0 + kZ * a.error + 1e-6) << "r " << r << " at " << theta << "°";
            if (r == 0.0f) {
                EXPECT_NEAR(a.mean, 1.0, 1e-6);  // a perfect white mirror
            }
        }
}

TEST(Pbr, WhiteDielectricReflectsMoreThanItReceivesAtGrazingAngles) {
    // Appendix B's fresnel_mix weighs the diffuse base by 1 − F(ωo·h), which
    // does not remove the energy that the specular layer reflects: the
    // specification says it "breaks ... energy conservation". A white
    // dielectric therefore has an albedo above 1 towards grazing view angles
    // (and just below 1 head-on); this pins that behaviour as Appendix B's.
    const Material m = pbr(Vec3{1.0f}, 0.0f, 0.3f);
    const Albedo grazing = albedo(m, polar(80, 0.3), 0, 20000, 7);
    EXPECT_GT(grazing.mean, 1.0 + kZ * grazing.error);
    const Albedo head_on = albedo(m, polar(0, 0.3), 0, 20000, 8);
    EXPECT_LE(head_on.mean, 1.0 + kZ * head_on.error);
}

TEST(Pbr, RoughnessZeroIsADeltaMirrorOverTheDiffuseBase) {
    // Below α = 1e-3 the specular part is a mirror; the material is delta
    // (lights cannot be sampled for it) only when nothing diffuse remains.
    EXPECT_FALSE(is_delta_bsdf(pbr(Vec3{0.5f}, 0.0f, 0.0f)));
    EXPECT_FALSE(is_delta_bsdf(pbr(Vec3{0.5f}, 0.99f, 0.0f)));
    EXPECT_TRUE(is_delta_bsdf(pbr(Vec3{0.5f}, 1.0f, 0.0f)));
    EXPECT_TRUE(is_delta_bsdf(pbr(Vec3{0.5f}, 1.0f, std::sqrt(0.999e-3f))));
    EXPECT_FALSE(is_delta_bsdf(pbr(Vec3{0.5f}, 1.0f, std::sqrt(1.001e-3f))));
    EXPECT_FALSE(is_delta_bsdf(pbr(Vec3{0.5f}, 0.0f, 0.5f)));
    // eval holds the diffuse part only: at the mirror direction it is no larger than elsewhere.
    const Material m = pbr({0.6f, 0.6f, 0.6f}, 0.0f, 0.0f);
    const Vec3 wo = polar(40, 0.5), mirror = polar(40, 0.5 + kPi);
    EXPECT_LT(eval_bsdf(m, kFlat, wo, mirror).x, 0.6f / static_cast<float>(kPi));
    EXPECT_GT(eval_bsdf(m, kFlat, wo, mirror).x, 0.0f);
    // A smooth metal samples only the mirror, with its Schlick Fresnel.
    BsdfSample s;
    ASSERT_TRUE(sample_bsdf(pbr(Vec3{0.5f}, 1.0f, 0.0f), kFlat, wo, 0.999f, 0.1f, 0.9f, s));
    EXPECT_TRUE(s.delta);
    EXPECT_EQ(s.pdf, 1.0f);
    EXPECT_NEAR(s.weight.x, 0.5f + 0.5f * std::pow(1.0f - wo.z, 5.0f), 1e-6f);
    EXPECT_EQ(eval_bsdf(pbr(Vec3{0.5f}, 1.0f, 0.0f), kFlat, wo, s.wi), Vec3{0.0f});
    EXPECT_EQ(pdf_bsdf(pbr(Vec3{0.5f}, 1.0f, 0.0f), kFlat, wo, s.wi), 0.0f);
}

TEST(Pbr, EdgeCasesAreFinite) {
    const Material ms[] = {pbr(Vec3{0.5f}, 0, 0),
                           pbr(Vec3{0.5f}, 0.5f, std::sqrt(0.999e-3f)),
                           pbr(Vec3{0.5f}, 1, std::sqrt(1.001e-3f)),
                           pbr(Vec3{1.0f}, 0, 1),
                           pbr(Vec3{0.0f}, 1, 0.5f),
                           pbr(Vec3{0.0f}, 0, 0.5f, 1.0001f),
                           pbr(Vec3{1.0f}, 0, 0.2f, 50.0f)};
    // Grazing, exactly tangent, below a tilted n_s, normal.
    const Vec3 wos[] = {polar(89.99, 0.1), Vec3{1, 0, 0},        normalize(Vec3{1, 0, 1e-7f}),
                        polar(0, 0),       polar(80, 1.0 + kPi), Vec3{0, 0, 1}};
    const float us[] = {0.0f, 0.5f, 0x1.fffffep-1f};
    for (const Material& m : ms)
        for (const BsdfPoint& p : {kFlat, kTilted})
            for (const Vec3 wo : wos) {
                for (const Vec3 wi : wos) {
                    ASSERT_TRUE(is_finite(eval_bsdf(m, p, wo, wi)));
                    ASSERT_TRUE(std::isfinite(pdf_bsdf(m, p, wo, wi)));
                    ASSERT_GE(pdf_bsdf(m, p, wo, wi), 0.0f);
                }
                for (const float a : us)
                    for (const float b : us)
                        for (const float c : us) {
                            BsdfSample s;
                            if (!sample_bsdf(m, p, wo, a, b, c, s)) continue;
                            ASSERT_TRUE(is_finite(s.weight) && is_finite(s.wi) && std::isfinite(s.pdf));
                            ASSERT_GT(s.pdf, 0.0f);
                            ASSERT_NEAR(length(s.wi), 1.0f, 1e-4f);
                        }
            }
}

}  // namespace
}  // namespace sombra
