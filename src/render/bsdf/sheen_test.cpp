// Tests of the Charlie sheen lobe and its albedo table (render/bsdf/sheen.h):
// the lobe against an independent double-precision transcription of the
// formulas in KHR_materials_sheen's implementation notes
// (render/bsdf/pbr_test_util.h), and the table
// against a brute-force integral of that transcription on a fine uniform
// grid (a different rule from the table's, at nodes and between them).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "render/bsdf/bsdf_test_util.h"
#include "render/bsdf/pbr_test_util.h"
#include "render/bsdf/sheen.h"

namespace sombra {
namespace {

using bsdf_testing::random_upper;

constexpr double kPi = 3.14159265358979323846;

double ref_sheen(double vx, double vy, double vz, double lx, double ly, double lz, double r) {
    return pbr_reference::sheen_lobe({vx, vy, vz}, {lx, ly, lz}, r);
}

// E(μ, r) by brute force: the midpoint rule on a uniform n × 2n grid of
// (cos θ_i, φ_i) over the whole hemisphere.
double brute_albedo(double mu, double r, int n) {
    const double vx = std::sqrt(1.0 - mu * mu);
    double sum = 0.0;
    for (int a = 0; a < n; ++a) {
        const double z = (a + 0.5) / n, s = std::sqrt(1.0 - z * z);
        for (int b = 0; b < 2 * n; ++b) {
            const double phi = (b + 0.5) * kPi / n;
            sum += ref_sheen(vx, 0.0, mu, s * std::cos(phi), s * std::sin(phi), z, r) * z;
        }
    }
    return sum * (1.0 / n) * (kPi / n);
}

TEST(SheenLobe, MatchesTheExtensionsFormulas) {
    std::uint64_t key = 70;
    for (const float r : {0.1f, 0.3f, 0.5f, 0.8f, 1.0f}) {
        ++key;
        for (std::uint32_t i = 0; i < 4000; ++i) {
            const Vec3 wo = random_upper(i, key), wi = random_upper(i, key + 100);
            if (wo.z < 1e-3f || wi.z < 1e-3f) continue;
            const double expected = ref_sheen(wo.x, wo.y, wo.z, wi.x, wi.y, wi.z, r);
            ASSERT_NEAR(eval_sheen_lobe(wo, wi, r), expected, 2e-4 * expected + 1e-7)
                << "r " << r << " wo.z " << wo.z << " wi.z " << wi.z;
        }
    }
}

TEST(SheenLobe, IsSymmetricZeroBelowAndFiniteAtTheFloorRoughness) {
    for (std::uint32_t i = 0; i < 2000; ++i) {
        const Vec3 wo = random_upper(i, 81), wi = random_upper(i, 82);
        for (const float r : {0.0f, 0.2f, 0.9f}) {
            const float f = eval_sheen_lobe(wo, wi, r);
            EXPECT_TRUE(std::isfinite(f) && f >= 0.0f) << r;
            EXPECT_NEAR(f, eval_sheen_lobe(wi, wo, r), 1e-5f * f) << r;
            EXPECT_EQ(eval_sheen_lobe(wo, Vec3{wi.x, wi.y, -wi.z}, r), 0.0f);
        }
        // Below the floor roughness the lobe is the floor's.
        EXPECT_EQ(eval_sheen_lobe(wo, wi, 0.0f), eval_sheen_lobe(wo, wi, kMinSheenRoughness));
    }
}

// The table's entries (its own quadrature) against brute force, at nodes
// where the lobe is broad enough for the uniform grid to resolve it.
TEST(SheenAlbedo, TableNodesMatchBruteForce) {
    const SheenAlbedoTable table = make_sheen_albedo_table();
    constexpr int last = kSheenTableSize - 1;
    for (const auto& [i, j] : {std::pair{1, 31}, {4, 31}, {16, 31}, {31, 31}, {3, 8}, {8, 8}, {16, 16}, {24, 20}}) {
        const double mu = double(i) / last, r = double(j) / last;
        const double expected = brute_albedo(mu, r, 1000);
        EXPECT_NEAR(table.e[j][i], expected, 2e-3 + 1e-3 * expected) << "mu " << mu << " r " << r;
        // The lookup at a node returns the node.
        EXPECT_NEAR(sheen_albedo(float(mu), float(r)), table.e[j][i], 1e-6f) << "mu " << mu << " r " << r;
    }
}

// Between nodes the lookup is bilinear: its error is at most h²/8 (h = 1/31)
// times the sum of E's second derivatives along the axes, whose second
// differences over the nodes with μ ≥ 0.1 and r ≥ 0.3 are at most 22 (μ)
// and 4 (r): 0.0034, plus the brute force's own 10⁻³.
TEST(SheenAlbedo, LookupsBetweenNodesMatchBruteForce) {
    for (const auto& [mu, r] : {std::pair{0.15, 0.35}, {0.42, 0.61}, {0.77, 0.93}, {0.55, 0.48}, {0.95, 0.71}}) {
        const double expected = brute_albedo(mu, r, 1000);
        EXPECT_NEAR(sheen_albedo(float(mu), float(r)), expected, 0.0045) << "mu " << mu << " r " << r;
    }
}

// E grows toward grazing views and with roughness at normal incidence, and
// is 0 where the fibres cannot reflect toward ωo (a smooth sheen seen from above).
TEST(SheenAlbedo, ShapeAsThePaperShowsIt) {
    EXPECT_LT(sheen_albedo(1.0f, 0.1f), 1e-4f);
    EXPECT_GT(sheen_albedo(1.0f, 1.0f), sheen_albedo(1.0f, 0.5f));
    EXPECT_GT(sheen_albedo(0.2f, 0.6f), sheen_albedo(0.8f, 0.6f));
}

}  // namespace
}  // namespace sombra
