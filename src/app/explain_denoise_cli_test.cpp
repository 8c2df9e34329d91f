// `sombra explain --denoise` through the real executable (spec §25): the
// pixel's denoised value is the pixel `render --denoise` writes, its raw
// value the noisy render's, and the weights it lists add up to 1 and to
// the value; the text lists the ten largest terms, the SVG maps them.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

const std::string kSource = SOMBRA_SOURCE_DIR;

// Small enough to stay quick, large enough that the weights reach far.
const std::string kArgs = "--width 48 --height 40 --spp 4 --threads 2 --quiet";

class ExplainDenoiseCli : public CliFixture {
protected:
    // The repository's path-traced Cornell box: noisy at 4 spp.
    std::string cornell() const { return shell_quote(kSource + "/scenes/cornell-box-path.json"); }

    std::string explain(int x, int y, const std::string& extra) {
        return "explain " + cornell() + " " + std::to_string(x) + " " + std::to_string(y) + " --denoise " + kArgs +
               " " + extra;
    }

    // Pixel (x, y) of a PFM (rows bottom to top) as three floats.
    static std::array<float, 3> pixel_of(const Pfm& image, int x, int y) {
        const std::size_t p = (static_cast<std::size_t>(image.height - 1 - y) * static_cast<std::size_t>(image.width) +
                               static_cast<std::size_t>(x)) *
                              3;
        return {image.rgb[p], image.rgb[p + 1], image.rgb[p + 2]};
    }

    static std::array<float, 3> floats_of(const nlohmann::json& rgb) {
        return {static_cast<float>(rgb[0].get<double>()), static_cast<float>(rgb[1].get<double>()),
                static_cast<float>(rgb[2].get<double>())};
    }
};

TEST_F(ExplainDenoiseCli, JsonValueIsTheDenoisedPixelAndTheWeightsMakeIt) {
    ASSERT_EQ(run("render " + cornell() + " -o denoised.pfm --denoise " + kArgs).status, 0);
    ASSERT_EQ(run("render " + cornell() + " -o raw.pfm " + kArgs).status, 0);
    const Pfm denoised = read_pfm(dir_ / "denoised.pfm"), raw = read_pfm(dir_ / "raw.pfm");
    ASSERT_EQ(denoised.width, 48);
    ASSERT_EQ(raw.width, 48);
    // The middle of the back wall, an edge of the tall box, a corner of the image.
    for (const auto& [x, y] : {std::pair{24, 14}, std::pair{17, 30}, std::pair{0, 39}}) {
        const RunResult r = run(explain(x, y, "--json"));
        ASSERT_EQ(r.status, 0) << r.err;
        const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
        ASSERT_FALSE(j.is_discarded()) << r.out;
        ASSERT_TRUE(j.contains("denoise")) << r.out;
        const nlohmann::json& d = j["denoise"];
        const std::string at = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
        EXPECT_EQ(floats_of(d["value"]), pixel_of(denoised, x, y)) << at;
        EXPECT_EQ(floats_of(d["raw"]), pixel_of(raw, x, y)) << at;
        ASSERT_TRUE(d["weights"].is_array());
        ASSERT_GT(d["weights"].size(), 10u) << at;

        double weight_sum[3] = {}, sum[3] = {}, magnitude[3] = {};
        for (const nlohmann::json& term : d["weights"]) {
            const int qx = term["pixel"][0].get<int>(), qy = term["pixel"][1].get<int>();
            EXPECT_TRUE(qx >= 0 && qx < 48 && qy >= 0 && qy < 40) << term.dump();
            EXPECT_TRUE(term["half"] == "a" || term["half"] == "b") << term.dump();
            bool nonzero = false;
            for (int c = 0; c < 3; ++c) {
                const double w = term["w"][c].get<double>(), c_q = term["raw"][c].get<double>();
                nonzero = nonzero || w != 0.0;
                weight_sum[c] += w;
                sum[c] += w * c_q;
                magnitude[c] += std::abs(w * c_q);
            }
            EXPECT_TRUE(nonzero) << "only terms with a nonzero weight: " << term.dump();
        }
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(weight_sum[c], 1.0, 1e-4) << at << " channel " << c;
            const double value = d["value"][c].get<double>();
            if (d["clamped"][c].get<bool>()) {
                EXPECT_LT(sum[c], 0.0) << at << " channel " << c;
                EXPECT_EQ(value, 0.0);
            } else {
                EXPECT_NEAR(sum[c], value, 1e-4 * magnitude[c] + 1e-6) << at << " channel " << c;
            }
        }
    }
}

TEST_F(ExplainDenoiseCli, WithoutDenoiseTheStoryHasNoDenoising) {
    const RunResult r = run("explain " + cornell() + " 24 14 --json " + kArgs);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(nlohmann::json::parse(r.out).contains("denoise"));
    const RunResult text = run("explain " + cornell() + " 24 14 " + kArgs);
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_EQ(text.out.find("Denoised"), std::string::npos);
}

TEST_F(ExplainDenoiseCli, TextListsTheTenLargestTerms) {
    const RunResult r = run(explain(24, 14, ""));
    ASSERT_EQ(r.status, 0) << r.err;
    const std::size_t section = r.out.find("\nDenoised pixel (24, 14)");
    ASSERT_NE(section, std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Value of this sample"), std::string::npos) << "spec §14's story comes first";
    const std::string tail = r.out.substr(section);
    for (const char* words : {"raw ", "denoised ", "Σ w·c", "terms with a nonzero weight", "add up to",
                              "the 10 largest, by |w·c| summed over R, G and B"})
        EXPECT_NE(tail.find(words), std::string::npos) << words << " in:\n" << tail;
    std::istringstream lines(tail);
    int rows = 0;
    const std::regex row(R"(^    \(\d+, \d+\) +[AB] +\(.*)");
    for (std::string line; std::getline(lines, line);) rows += std::regex_match(line, row) ? 1 : 0;
    EXPECT_EQ(rows, 10) << tail;
}

TEST_F(ExplainDenoiseCli, SvgMapsTheWeights) {
    const RunResult r = run(explain(24, 14, "--svg story.svg"));
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string svg = read_text(dir_ / "story.svg");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    const std::size_t map = svg.find("<g id=\"denoise-weights\">");
    ASSERT_NE(map, std::string::npos);
    EXPECT_NE(svg.find("<title>(24, 14): w = ", map), std::string::npos) << "the pixel's own square";
    EXPECT_NE(svg.find("url(#denoise-scale)", map), std::string::npos) << "the scale";
    EXPECT_NE(svg.find("4 spp, before denoising"), std::string::npos);
    expect_no_temp_files();
}

TEST_F(ExplainDenoiseCli, OneSampleIsACommandLineError) {
    write_text(dir_ / "s.json", scene());  // 1 spp
    for (const std::string args : {"explain s.json 5 5 --denoise --spp 1", "explain s.json 5 5 --denoise"}) {
        const RunResult r = run(args);
        EXPECT_EQ(r.status, 2) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: command line: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find("--denoise"), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
}

}  // namespace
