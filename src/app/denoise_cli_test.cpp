// Spec §25 from the command line: render --denoise, the noisy and denoise
// AOVs, `sombra denoise` of the layers (the same bytes as render
// --denoise), merge --denoise of shards, and the errors of each.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_fixture.h"
#include "image/image_io.h"

namespace {

using namespace sombra::cli_test;

class Denoise : public CliFixture {
protected:
    // 71 × 49 pixels: tiles and shard blocks cut by the image's edges.
    void SetUp() override {
        CliFixture::SetUp();
        write_text(dir_ / "s.json", scene(R"({"width": 71, "height": 49, "spp": 4, "integrator": "path"})"));
    }
    void render(const std::string& options) {
        const RunResult r = run("render s.json -q " + options);
        ASSERT_EQ(r.status, 0) << r.err;
    }
};

TEST_F(Denoise, DenoiseCommandGivesTheRendersBytesOnAnyThreadCount) {
    render("--denoise --threads 2 -o d.pfm");
    render("--denoise --threads 1 -o d1.pfm");
    render("--denoise -o d.exr");
    render("--aov denoise -o layers.exr");
    EXPECT_EQ(read_text(dir_ / "d1.pfm"), read_text(dir_ / "d.pfm"));
    for (const std::string ext : {"pfm", "exr"}) {
        const RunResult r = run("denoise layers.exr --threads 1 -o again." + ext);
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.err.find("sombra: denoised layers.exr (71x49)"), std::string::npos) << r.err;
        EXPECT_EQ(read_text(dir_ / ("again." + ext)), read_text(dir_ / ("d." + ext))) << ext;
    }
    // Denoised is not raw.
    render("-o raw.pfm");
    EXPECT_NE(read_text(dir_ / "raw.pfm"), read_text(dir_ / "d.pfm"));
}

TEST_F(Denoise, NoisyLayerIsTheImageBeforeDenoising) {
    render("--denoise --aov noisy,variance -o d.exr");
    render("--aov variance -o raw.exr");
    const sombra::ExrChannels denoised = sombra::read_exr_channels(dir_ / "d.exr");
    const sombra::ExrChannels raw = sombra::read_exr_channels(dir_ / "raw.exr");
    const auto channel = [](const sombra::ExrChannels& exr, const std::string& name) {
        for (std::size_t i = 0; i < exr.names.size(); ++i)
            if (exr.names[i] == name) return exr.values[i];
        ADD_FAILURE() << "no channel " << name;
        return std::vector<float>{};
    };
    for (const char* c : {"R", "G", "B"}) {
        EXPECT_EQ(channel(denoised, std::string("noisy.") + c), channel(raw, c));
        EXPECT_EQ(channel(denoised, std::string("variance.") + c), channel(raw, std::string("variance.") + c));
        EXPECT_NE(channel(denoised, c), channel(raw, c));
    }
}

TEST_F(Denoise, TheDenoiserReportsItsTime) {
    const RunResult r = run("render s.json --denoise --stats-json stats.json -o d.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find(", denoise "), std::string::npos) << r.err;
    const auto stats = nlohmann::json::parse(read_text(dir_ / "stats.json"));
    EXPECT_GT(stats.at("denoise_seconds").get<double>(), 0.0);
    // Under a time budget, which includes the denoiser.
    const RunResult timed = run("render s.json -q --denoise --time 1 -o t.png");
    EXPECT_EQ(timed.status, 0) << timed.err;
    EXPECT_TRUE(fs::exists(dir_ / "t.png"));
}

TEST_F(Denoise, FewerThanTwoSamplesOrNoisyWithoutDenoiseAreCommandLineErrors) {
    write_text(dir_ / "one.json", scene(R"({"width": 16, "height": 16, "spp": 1})"));
    for (const std::string args : {"render s.json --denoise --spp 1 -o out.png", "render one.json --denoise -o out.png",
                                   "render s.json --aov noisy -o out.exr", "explain s.json 3 3 --denoise --spp 1"}) {
        SCOPED_TRACE(args);
        const RunResult r = run(args);
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: command line: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
    EXPECT_NE(run("render one.json --denoise -o out.png").err.find("--denoise: needs at least 2 samples per pixel"),
              std::string::npos);
}

TEST_F(Denoise, BrokenInputsToTheDenoiseCommandAreOneErrorLine) {
    render("-o plain.exr");
    expect_input_error(run("denoise plain.exr -o out.png"), "plain.exr: no layer 'variance.R'");
    expect_input_error(run("denoise missing.exr -o out.png"), "missing.exr");
    write_text(dir_ / "text.exr", "not an image");
    expect_input_error(run("denoise text.exr -o out.png"), "text.exr");
    // A NaN where a colour should be.
    render("--aov denoise -o layers.exr");
    sombra::ExrChannels exr = sombra::read_exr_channels(dir_ / "layers.exr");
    std::vector<float> rgb(static_cast<std::size_t>(exr.width * exr.height) * 3, 0.0f);
    std::vector<sombra::ImageChannel> layers;
    for (std::size_t i = 0; i < exr.names.size(); ++i) {
        if (exr.names[i] == "denoise.B.G") exr.values[i][2 * 71 + 3] = std::numeric_limits<float>::quiet_NaN();
        if (exr.names[i].find('.') != std::string::npos) layers.push_back({exr.names[i], exr.values[i].data(), 1});
    }
    sombra::write_image(dir_ / "nan.exr", {exr.width, exr.height, rgb.data()}, {}, layers);
    expect_input_error(run("denoise nan.exr -o out.png"), "nan.exr: denoise.B.G: nan at pixel (3, 2)");
}

TEST_F(Denoise, MergedShardsDenoiseAsTheWholeRender) {
    for (int i = 0; i < 2; ++i)
        render("--denoise --shard " + std::to_string(i) + "/2 --threads " + std::to_string(i + 1) + " -o s" +
               std::to_string(i) + ".exr");
    render("--denoise -o whole.pfm");
    render("-o raw.pfm");
    ASSERT_EQ(run("merge -q s1.exr s0.exr --denoise -o merged.pfm").status, 0);
    EXPECT_EQ(read_text(dir_ / "merged.pfm"), read_text(dir_ / "whole.pfm"));
    // Without --denoise the merge is the raw render, as ever.
    ASSERT_EQ(run("merge -q s0.exr s1.exr -o merged-raw.pfm").status, 0);
    EXPECT_EQ(read_text(dir_ / "merged-raw.pfm"), read_text(dir_ / "raw.pfm"));
    // Shards without the layers cannot be denoised.
    for (int i = 0; i < 2; ++i) render("--shard " + std::to_string(i) + "/2 -o p" + std::to_string(i) + ".exr");
    expect_input_error(run("merge p0.exr p1.exr --denoise -o out.png"), "no layer 'variance.R'");
}

}  // namespace
