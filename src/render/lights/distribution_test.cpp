// Distribution1D / Distribution2D: probabilities follow the weights, the pdf
// integrates to 1, samples follow the pdf (χ²), and zero weights are never hit.
#include "render/lights/distribution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "render/chi2_test_util.h"

namespace sombra {
namespace {

constexpr int kChi2Tests = 3;  // the χ² tests in this file, for Šidák's correction
const double kAlpha = 1 - std::pow(1 - 0.01, 1.0 / kChi2Tests);

const std::vector<float> kWeights = {0.0f, 3.0f, 1.0f, 0.0f, 0.0f, 0.25f, 7.5f, 2.0f, 0.0f, 0.5f, 0.0f};

TEST(Chi2, IncompleteGammaKnownValues) {
    EXPECT_NEAR(chi2::gamma_q(1, 2), std::exp(-2.0), 1e-12);               // Q(1, x) = e^-x
    EXPECT_NEAR(chi2::gamma_q(0.5, 0.5 * 3.841458820694124), 0.05, 1e-9);  // χ²(1) at 95%
    EXPECT_NEAR(chi2::gamma_q(5, 0.5 * 23.209251158954356), 0.01, 1e-9);   // χ²(10) at 99%
}

TEST(Distribution1D, ProbabilitiesFollowTheWeights) {
    const Distribution1D d = make_distribution_1d(kWeights);
    ASSERT_EQ(size(d), 11);
    EXPECT_FLOAT_EQ(d.total, 14.25f);
    EXPECT_FLOAT_EQ(d.integral, 14.25f / 11);
    double sum_p = 0, integral_pdf = 0;
    for (int i = 0; i < size(d); ++i) {
        EXPECT_FLOAT_EQ(probability(d, i), kWeights[i] / 14.25f);
        EXPECT_FLOAT_EQ(pdf(d, i), kWeights[i] / (14.25f / 11));
        sum_p += probability(d, i);
        integral_pdf += pdf(d, i) / 11.0;
    }
    EXPECT_NEAR(sum_p, 1.0, 1e-6);
    EXPECT_NEAR(integral_pdf, 1.0, 1e-6);
    EXPECT_EQ(probability(d, -1), 0.0f);
    EXPECT_EQ(pdf(d, 11), 0.0f);

    // A dense deterministic sweep of u: each bin's share is its probability.
    const int sweep = 1 << 20;
    std::vector<int> hits(11);
    for (int k = 0; k < sweep; ++k) {
        const DiscreteSample s = sample_discrete(d, (static_cast<float>(k) + 0.5f) / sweep);
        ASSERT_GE(s.index, 0);
        ASSERT_LT(s.index, 11);
        ASSERT_GT(kWeights[s.index], 0.0f) << "zero weight chosen at u = " << k;
        EXPECT_EQ(s.probability, probability(d, s.index));
        ++hits[s.index];
    }
    for (int i = 0; i < 11; ++i) EXPECT_NEAR(hits[i] / double(sweep), probability(d, i), 2.0 / sweep);
}

TEST(Distribution1D, ZeroWeightsAreNeverChosenEvenOnBinEdges) {
    const Distribution1D d = make_distribution_1d(kWeights);
    for (const float edge : d.cdf)
        for (const float u : {edge, std::nextafter(edge, 0.0f), std::nextafter(edge, 1.0f), 0.0f, 1.0f,
                              std::numeric_limits<float>::quiet_NaN(), -0.5f, 2.0f}) {
            const ContinuousSample c = sample_continuous(d, u);
            ASSERT_GT(kWeights[c.index], 0.0f) << "u = " << u;
            ASSERT_GE(c.x, static_cast<float>(c.index) / 11.0f);
            ASSERT_LT(c.x, 1.0f);
            ASSERT_EQ(static_cast<int>(c.x * 11), c.index) << "x = " << c.x;
            ASSERT_GT(kWeights[sample_discrete(d, u).index], 0.0f);
        }
    // A weight small beside the others (but above float resolution, see the
    // header) still gets a bin that can be hit.
    const std::vector<float> tiny = {1e3f, 1e-3f, 1e3f};
    const Distribution1D t = make_distribution_1d(tiny);
    EXPECT_GT(t.cdf[2], t.cdf[1]);
}

TEST(Distribution1D, ContinuousSamplesFollowThePdfChi2) {
    const Distribution1D d = make_distribution_1d(kWeights);
    const int sub = 4, cells = 11 * sub, n = 200000;
    std::vector<double> observed(cells), expected(cells);
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int k = 0; k < n; ++k) {
        const ContinuousSample s = sample_continuous(d, uniform(rng));
        ASSERT_EQ(s.pdf, pdf(d, s.index));
        observed[std::min(cells - 1, static_cast<int>(s.x * cells))] += 1;
    }
    for (int c = 0; c < cells; ++c) expected[c] = n * pdf(d, c / sub) / cells;
    EXPECT_GT(chi2::pearson(observed, expected).p_value, kAlpha);
}

TEST(Distribution1D, AllZeroIsUniformAndEmptySamplesNothing) {
    const std::vector<float> zeros = {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f};
    const Distribution1D d = make_distribution_1d(zeros);
    EXPECT_EQ(d.integral, 0.0f);
    EXPECT_EQ(d.total, 0.0f);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(d.weight[i], 0.0f);
        EXPECT_EQ(probability(d, i), 0.25f);
        EXPECT_EQ(pdf(d, i), 1.0f);
    }
    EXPECT_EQ(sample_discrete(d, 0.6f).index, 2);
    const ContinuousSample c = sample_continuous(d, 0.6f);
    EXPECT_EQ(c.index, 2);
    EXPECT_NEAR(c.x, 0.6f, 1e-6f);
    EXPECT_EQ(c.pdf, 1.0f);

    const Distribution1D empty = make_distribution_1d({});
    EXPECT_EQ(size(empty), 0);
    EXPECT_EQ(sample_discrete(empty, 0.5f).index, -1);
    EXPECT_EQ(sample_continuous(empty, 0.5f).pdf, 0.0f);
    EXPECT_EQ(probability(empty, 0), 0.0f);
}

// A 5 × 4 grid with empty cells and an empty row.
const int kW = 5, kH = 4;
const std::vector<float> kGrid = {1, 0, 2, 0,    4,  //
                                  0, 0, 0, 0,    0,  //
                                  9, 3, 0, 0.5f, 1,  //
                                  0, 0, 6, 0,    0};

TEST(Distribution2D, PdfIntegratesToOneAndFollowsTheWeights) {
    const Distribution2D d = make_distribution_2d(kGrid, kW, kH);
    double sum = 0, integral = 0;
    for (const float w : kGrid) sum += w;
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
            const float p = pdf(d, (static_cast<float>(i) + 0.5f) / kW, (static_cast<float>(j) + 0.5f) / kH);
            EXPECT_NEAR(p, kGrid[j * kW + i] / sum * kW * kH, 1e-5) << i << ", " << j;
            integral += p / (kW * kH);
        }
    EXPECT_NEAR(integral, 1.0, 1e-6);
    EXPECT_EQ(pdf(make_distribution_2d({}, 0, 0), 0.5f, 0.5f), 0.0f);
    EXPECT_EQ(sample(make_distribution_2d({}, 0, 0), 0.5f, 0.5f).pdf, 0.0f);
}

TEST(Distribution2D, SamplesFollowThePdfChi2AndSkipEmptyCells) {
    const Distribution2D d = make_distribution_2d(kGrid, kW, kH);
    const int sub = 3, cw = kW * sub, ch = kH * sub, n = 300000;
    std::vector<double> observed(cw * ch), expected(cw * ch);
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int k = 0; k < n; ++k) {
        const Sample2D s = sample(d, uniform(rng), uniform(rng));
        ASSERT_GE(s.u, 0.0f);
        ASSERT_LT(s.u, 1.0f);
        ASSERT_GE(s.v, 0.0f);
        ASSERT_LT(s.v, 1.0f);
        ASSERT_GT(kGrid[s.row * kW + s.column], 0.0f);
        ASSERT_NEAR(s.pdf, pdf(d, s.u, s.v), 1e-5f * s.pdf);
        observed[std::min(ch - 1, int(s.v * ch)) * cw + std::min(cw - 1, int(s.u * cw))] += 1;
    }
    for (int j = 0; j < ch; ++j)
        for (int i = 0; i < cw; ++i)
            expected[j * cw + i] = n *
                                   pdf(d, (static_cast<float>(i) + 0.5f) / static_cast<float>(cw),
                                       (static_cast<float>(j) + 0.5f) / static_cast<float>(ch)) /
                                   (cw * ch);
    EXPECT_GT(chi2::pearson(observed, expected).p_value, kAlpha);
}

TEST(Distribution2D, U1ChoosesTheColumnU2TheRow) {
    const std::vector<float> ones(6, 1.0f);
    const Distribution2D d = make_distribution_2d(ones, 3, 2);
    const Sample2D s = sample(d, 0.9f, 0.1f);
    EXPECT_EQ(s.column, 2);
    EXPECT_EQ(s.row, 0);
    EXPECT_NEAR(s.u, 0.9f, 1e-6f);
    EXPECT_NEAR(s.v, 0.1f, 1e-6f);
    EXPECT_NEAR(s.pdf, 1.0f, 1e-6f);
    const Distribution2D zero = make_distribution_2d(std::vector<float>(6, 0.0f), 3, 2);
    EXPECT_EQ(zero.marginal.integral, 0.0f);
    EXPECT_NEAR(sample(zero, 0.4f, 0.7f).pdf, 1.0f, 1e-6f);
    EXPECT_EQ(pdf(zero, 0.4f, 0.7f), 1.0f);
}

}  // namespace
}  // namespace sombra
