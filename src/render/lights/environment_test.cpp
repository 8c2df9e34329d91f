// The environment light: the mapping of spec §10 texel by texel, and
// sampling checked against its pdf (χ² over the sphere), its integral
// (Monte Carlo against quadrature) and eval (pdf > 0 wherever eval > 0).
#include "render/lights/environment.h"

#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <random>
#include <vector>

#include "render/chi2_test_util.h"

namespace sombra {
namespace {

constexpr double kPi = 3.14159265358979323846;

// --- χ² over the sphere, with the texel edges as bin cuts ---

constexpr int kChi2Tests = 3;  // χ² tests in this file, for Šidák's correction
const double kAlpha = 1 - std::pow(1 - 0.01, 1.0 / kChi2Tests);

// Unit direction for z = cos θ ∈ [−1, 1] (about +y) and φ ∈ [0, 2π).
Vec3 sphere_direction(double cos_theta, double phi) {
    const double r = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
    return {static_cast<float>(r * std::cos(phi)), static_cast<float>(cos_theta),
            static_cast<float>(r * std::sin(phi))};
}

// Draws n samples and compares their histogram over (cos θ, φ) bins, φ =
// atan2(z, x), with the pdf integrated over each bin; returns the p-value
// (bins expecting fewer than 5 merged). The pdf of a map jumps at texel
// edges, so each bin is cut there first (rows at cos θ = cos(πj/H), columns
// at φ = 2π(i/W − ½) − π/2 − rotation, from spec §10) and each piece
// integrated by the midpoint rule: no piece straddles a jump.
double sphere_chi2(const Environment& env, int n, std::uint32_t seed) {
    const int nc = 32, np = 64, sub = 3;
    std::vector<double> observed(nc * np), expected(nc * np);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int k = 0; k < n; ++k) {
        EnvironmentSample s;
        if (!sample_environment(env, uniform(rng), uniform(rng), s)) continue;
        double phi = std::atan2(s.direction.z, s.direction.x);
        if (phi < 0) phi += 2 * kPi;
        const int c = std::clamp(static_cast<int>((s.direction.y + 1) / 2 * nc), 0, nc - 1);
        const int p = std::clamp(static_cast<int>(phi / (2 * kPi) * np), 0, np - 1);
        observed[c * np + p] += 1;
    }
    std::vector<double> z_edges, phi_edges;
    const int w = env.image.width, h = env.image.height;
    for (int j = 0; j <= h; ++j) z_edges.push_back(std::cos(kPi * j / h));
    const double rotation = env.rotate_y_degrees * kPi / 180;
    for (int i = 0; i < w; ++i) {
        const double phi = 2 * kPi * (double(i) / w - 0.5) - kPi / 2 - rotation;
        phi_edges.push_back(phi - 2 * kPi * std::floor(phi / (2 * kPi)));
    }
    // The range [a, b] cut at the edges inside it.
    const auto cut = [](double a, double b, const std::vector<double>& edges) {
        std::vector<double> points = {a, b};
        for (const double e : edges)
            if (e > a && e < b) points.push_back(e);
        std::sort(points.begin(), points.end());
        return points;
    };
    for (int c = 0; c < nc; ++c)
        for (int p = 0; p < np; ++p) {
            const auto zs = cut(-1 + c * 2.0 / nc, -1 + (c + 1) * 2.0 / nc, z_edges);
            const auto phis = cut(p * 2 * kPi / np, (p + 1) * 2 * kPi / np, phi_edges);
            double sum = 0;
            for (std::size_t a = 0; a + 1 < zs.size(); ++a)
                for (std::size_t b = 0; b + 1 < phis.size(); ++b) {
                    const double dz = (zs[a + 1] - zs[a]) / sub, dphi = (phis[b + 1] - phis[b]) / sub;
                    for (int x = 0; x < sub; ++x)
                        for (int y = 0; y < sub; ++y)
                            sum += pdf_environment(env, sphere_direction(zs[a] + (x + 0.5) * dz,
                                                                         phis[b] + (y + 0.5) * dphi)) *
                                   dz * dphi;
                }
            expected[c * np + p] = sum * n;
        }
    return chi2::pearson(observed, expected).p_value;
}

// ∫ luminance(eval) dω by the midpoint rule on a fine (cos θ, φ) grid.
double quadrature(const Environment& env) {
    const int nc = 1024, np = 2048;
    double sum = 0;
    for (int c = 0; c < nc; ++c)
        for (int p = 0; p < np; ++p)
            sum +=
                luminance(eval_environment(env, sphere_direction(-1 + (c + 0.5) * 2.0 / nc, (p + 0.5) * 2 * kPi / np)));
    return sum * (2.0 / nc) * (2 * kPi / np);
}

HdrImage make_image(int w, int h, const std::function<Vec3(int, int)>& texel) {
    HdrImage image{w, h, {}};
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const Vec3 c = texel(i, j);
            image.rgb.insert(image.rgb.end(), {c.x, c.y, c.z});
        }
    return image;
}

// The map-frame direction of (u, v) (no rotation): the inverse of spec §10.
Vec3 direction_of(double u, double v) {
    const double theta = v * kPi, phi = 2 * kPi * (u - 0.5);
    return {static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta)),
            static_cast<float>(-std::sin(theta) * std::cos(phi))};
}

void expect_near(Vec3 a, Vec3 b, const char* what) {
    EXPECT_NEAR(a.x, b.x, 1e-4f) << what;
    EXPECT_NEAR(a.y, b.y, 1e-4f) << what;
    EXPECT_NEAR(a.z, b.z, 1e-4f) << what;
}

// Texel (i, j) of the 8 × 4 test map holds (i, j, 1).
const HdrImage kGridMap = make_image(8, 4, [](int i, int j) { return Vec3(float(i), float(j), 1.0f); });
Vec3 grid(float i, float j) { return {i, j, 1.0f}; }

TEST(EnvironmentMapping, AxesReadTheTexelsOfSpec10) {
    const Environment env = make_map_environment(kGridMap, 1.0f, 0.0f);
    // −z: (u, v) = (0.5, 0.5), the centre, between columns 3, 4 and rows 1, 2.
    expect_near(eval_environment(env, {0, 0, -1}), grid(3.5f, 1.5f), "-z");
    expect_near(eval_environment(env, {1, 0, 0}), grid(5.5f, 1.5f), "+x: u = 0.75");
    expect_near(eval_environment(env, {-1, 0, 0}), grid(1.5f, 1.5f), "-x: u = 0.25");
    // +z: u = 1 (or 0), on the seam: half column 7, half column 0.
    expect_near(eval_environment(env, {0, 0, 1}), grid(3.5f, 1.5f), "+z: (7 + 0) / 2");
    // +y: v = 0, clamped to the top row; −y: v = 1, the bottom row.
    EXPECT_NEAR(eval_environment(env, {0, 1, 0}).y, 0.0f, 1e-6f);
    EXPECT_NEAR(eval_environment(env, {0, -1, 0}).y, 3.0f, 1e-6f);
    // A texel centre reads that texel alone.
    expect_near(eval_environment(env, direction_of(6.5 / 8, 2.5 / 4)), grid(6, 2), "texel (6, 2)");
    expect_near(eval_environment(env, direction_of(0.5 / 8, 0.5 / 4)), grid(0, 0), "texel (0, 0)");
}

TEST(EnvironmentMapping, BilinearWrapsInUAndClampsInV) {
    const Environment env = make_map_environment(kGridMap, 2.0f, 0.0f);  // and scale multiplies
    // Between texel centres (2, 1), (3, 1), (2, 2), (3, 2) at fractions 0.25, 0.75.
    const Vec3 a = eval_environment(env, direction_of((2.5 + 0.25) / 8, (1.5 + 0.75) / 4));
    expect_near(a, 2.0f * grid(2.25f, 1.75f), "bilinear");
    // u wraps: a quarter texel left of column 0's centre is 3/4 column 0, 1/4 column 7.
    const Vec3 w = eval_environment(env, direction_of(0.25 / 8, 2.5 / 4));
    expect_near(w, 2.0f * grid(0.75f * 0 + 0.25f * 7, 2), "wrap");
    // v clamps: above row 0's centre, and below row 3's, the row alone.
    expect_near(eval_environment(env, direction_of(4.5 / 8, 0.2 / 4)), 2.0f * grid(4, 0), "top");
    expect_near(eval_environment(env, direction_of(4.5 / 8, 3.9 / 4)), 2.0f * grid(4, 3), "bottom");
}

TEST(EnvironmentMapping, RotateYTurnsTheMapAboutPlusY) {
    // Read at R_y(−θ)·d: with θ = 90°, −x sees the centre (what −z saw) and
    // −z sees what +x saw: the map turned right-handedly, −z → −x.
    const Environment plain = make_map_environment(kGridMap, 1.0f, 0.0f);
    const Environment turned = make_map_environment(kGridMap, 1.0f, 90.0f);
    expect_near(eval_environment(turned, {-1, 0, 0}), eval_environment(plain, {0, 0, -1}), "-x");
    expect_near(eval_environment(turned, {0, 0, -1}), eval_environment(plain, {1, 0, 0}), "-z");
    expect_near(eval_environment(turned, {0, 0, 1}), eval_environment(plain, {-1, 0, 0}), "+z");
    const Vec3 d = normalize({0.3f, 0.5f, -0.8f});
    const Environment thirty = make_map_environment(kGridMap, 1.0f, 30.0f);
    const float c = std::cos(float(kPi) / 6), s = std::sin(float(kPi) / 6);
    const Vec3 turned_d{c * d.x + s * d.z, d.y, -s * d.x + c * d.z};  // R_y(30°)·d
    expect_near(eval_environment(thirty, turned_d), eval_environment(plain, d), "30°");
}

// A 64 × 32 map: dim sky, a black band, a bright spot.
HdrImage spot_map() {
    return make_image(64, 32, [](int i, int j) {
        if (j >= 20 && j < 24) return Vec3(0.0f);
        if (i >= 40 && i < 43 && j >= 6 && j < 8) return Vec3(300.0f, 200.0f, 100.0f);
        return Vec3(0.1f + 0.01f * float(i % 7), 0.2f, 0.3f + 0.02f * float(j % 5));
    });
}

TEST(Environment, SamplesMatchEvalAndPdfExactly) {
    const Environment env = make_map_environment(spot_map(), 1.5f, 30.0f);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int k = 0; k < 20000; ++k) {
        EnvironmentSample s;
        if (!sample_environment(env, uniform(rng), uniform(rng), s)) continue;
        ASSERT_NEAR(length(s.direction), 1.0f, 1e-5f);
        ASSERT_EQ(s.radiance, eval_environment(env, s.direction));
        ASSERT_EQ(s.pdf, pdf_environment(env, s.direction));
        ASSERT_GT(s.pdf, 0.0f);
        ASSERT_TRUE(std::isfinite(s.pdf));
    }
}

TEST(Environment, PdfIsPositiveWhereverEvalIs) {
    for (const float rotate : {0.0f, 37.0f}) {
        const Environment env = make_map_environment(spot_map(), 1.0f, rotate);
        int zero_eval = 0;
        for (int c = 0; c <= 600; ++c)
            for (int p = 0; p < 1200; ++p) {
                const Vec3 d = sphere_direction(-1 + c * 2.0 / 600, p * 2 * kPi / 1200);
                const float pdf = pdf_environment(env, d);
                ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0f);
                if (max_component(eval_environment(env, d)) > 0.0f) {
                    if (std::fabs(d.y) < 1.0f) {
                        ASSERT_GT(pdf, 0.0f) << d.x << " " << d.y << " " << d.z;
                    }
                } else {
                    ++zero_eval;
                }
            }
        EXPECT_GT(zero_eval, 0) << "the black band is seen";
        EXPECT_EQ(pdf_environment(env, {0, 1, 0}), 0.0f);  // pole: sin θ = 0
        EXPECT_EQ(pdf_environment(env, {0, -1, 0}), 0.0f);
    }
}

TEST(Environment, SamplingFollowsThePdfChi2SpotMap) {
    const Environment env = make_map_environment(spot_map(), 1.0f, 30.0f);
    EXPECT_GT(sphere_chi2(env, 400000, 11), kAlpha);
}

TEST(Environment, SamplingFollowsThePdfChi2ConstantEnvironment) {
    const Environment env = make_constant_environment({0.5f, 1.0f, 2.0f});
    EXPECT_GT(sphere_chi2(env, 200000, 12), kAlpha);
}

// sunset.exr, its (few) negative pixels made 0 (spec §10 makes read_hdr_image
// refuse them) and downsampled 2×2.
HdrImage shared_sunset(bool& found) {
    const std::filesystem::path file = std::filesystem::path(SOMBRA_SHARED_DIR) / "envmaps" / "sunset.exr";
    found = std::filesystem::exists(file);
    if (!found) return {};
    Imf::InputFile in(file.c_str());
    const Imath::Box2i window = in.header().dataWindow();
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    std::vector<float> rgb(static_cast<std::size_t>(w) * h * 3);
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (std::size_t c = 0; c < 3; ++c)
        frame.insert(names[c],
                     Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, window, 12, 12 * static_cast<std::size_t>(w)));
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);
    return make_image(w / 2, h / 2, [&](int i, int j) {
        Vec3 sum(0.0f);
        for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
                const float* p = &rgb[3 * ((static_cast<std::size_t>(2 * j + b)) * w + 2 * i + a)];
                sum += max(Vec3(p[0], p[1], p[2]), Vec3(0.0f));
            }
        return sum * 0.25f;
    });
}

TEST(Environment, SamplingFollowsThePdfChi2SharedSunset) {
    bool found = false;
    const HdrImage image = shared_sunset(found);
    if (!found) GTEST_SKIP() << "shared/envmaps/sunset.exr is missing";
    EXPECT_GT(sphere_chi2(make_map_environment(image, 1.0f, 0.0f), 400000, 13), kAlpha);
}

// The Monte Carlo estimate mean(L/pdf) of ∫ L dω against quadrature, as a z-test.
void expect_integral_agrees(const Environment& env, std::uint32_t seed) {
    const double reference = quadrature(env);
    const int n = 400000;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    double sum = 0, sum2 = 0;
    for (int k = 0; k < n; ++k) {
        EnvironmentSample s;
        const double f = sample_environment(env, uniform(rng), uniform(rng), s) ? luminance(s.radiance) / s.pdf : 0.0;
        sum += f;
        sum2 += f * f;
    }
    const double mean = sum / n, variance = (sum2 / n - mean * mean) / (n - 1);
    const double sigma = std::sqrt(variance + (2e-3 * reference) * (2e-3 * reference));  // and quadrature's error
    EXPECT_LT(std::fabs(mean - reference) / sigma, 4.0) << "MC " << mean << " quadrature " << reference;
    // The power proxy integrates the texels piecewise constant: close to the bilinear integral.
    EXPECT_NEAR(environment_power_proxy(env), reference, 0.03 * reference);
}

TEST(Environment, MonteCarloIntegralAgreesWithQuadrature) {
    expect_integral_agrees(make_map_environment(spot_map(), 2.0f, 30.0f), 21);
    expect_integral_agrees(make_constant_environment({0.5f, 1.0f, 2.0f}), 22);
    bool found = false;
    const HdrImage sunset = shared_sunset(found);
    if (!found) GTEST_SKIP() << "shared/envmaps/sunset.exr is missing";
    expect_integral_agrees(make_map_environment(sunset, 1.0f, -45.0f), 23);
}

TEST(Environment, ConstantAndBlack) {
    const Environment sky = make_constant_environment({0.5f, 1.0f, 2.0f});
    EXPECT_FALSE(is_black(sky));
    EXPECT_EQ(eval_environment(sky, {0, 0, -1}), Vec3(0.5f, 1.0f, 2.0f));
    EXPECT_FLOAT_EQ(pdf_environment(sky, {1, 0, 0}), float(1 / (4 * kPi)));
    EXPECT_FLOAT_EQ(environment_power_proxy(sky), float(4 * kPi) * luminance({0.5f, 1.0f, 2.0f}));

    EnvironmentSample s;
    for (const Environment& black : {make_constant_environment(Vec3(0.0f)),
                                     make_map_environment(make_image(4, 2, [](int, int) { return Vec3(0.0f); }), 1, 0),
                                     make_map_environment(spot_map(), 0.0f, 0.0f)}) {
        EXPECT_TRUE(is_black(black));
        EXPECT_FALSE(sample_environment(black, 0.3f, 0.6f, s));
        EXPECT_EQ(pdf_environment(black, {0, 0, -1}), 0.0f);
        EXPECT_EQ(environment_power_proxy(black), 0.0f);
        EXPECT_EQ(eval_environment(black, {0, 0, -1}), Vec3(0.0f));
    }
}

}  // namespace
}  // namespace sombra
