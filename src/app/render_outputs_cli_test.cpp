// Spec §18 from the command line: --time, --noise-threshold, --min-spp and
// --aov, their statistics, the EXR layers as a reader sees them, and the
// command-line errors.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

class RenderOutputs : public CliFixture {};

TEST_F(RenderOutputs, TimeBudgetImageEqualsTheSppItReached) {
    write_text(dir_ / "s.json", scene());
    const RunResult timed =
        run("render s.json -o timed.pfm --integrator path --time 0.3 --quiet --stats-json timed.json");
    ASSERT_EQ(timed.status, 0) << timed.err;
    const auto stats = nlohmann::json::parse(read_text(dir_ / "timed.json"));
    ASSERT_TRUE(stats["spp_reached"].is_number_integer()) << stats.dump();
    const int reached = stats["spp_reached"].get<int>();
    EXPECT_GE(reached, 2);
    EXPECT_EQ(reached % 2, 0) << "passes add two samples each";
    EXPECT_EQ(stats["passes"].get<int>(), reached / 2);
    EXPECT_EQ(stats["spp"].get<int>(), reached);
    const RunResult fixed =
        run("render s.json -o fixed.pfm --integrator path --quiet --spp " + std::to_string(reached));
    ASSERT_EQ(fixed.status, 0) << fixed.err;
    EXPECT_EQ(read_text(dir_ / "timed.pfm"), read_text(dir_ / "fixed.pfm"));
}

TEST_F(RenderOutputs, SppLimitsATimeBudget) {
    write_text(dir_ / "s.json", scene());
    const RunResult r = run("render s.json -o out.pfm --time 100 --spp 5 --quiet --stats-json stats.json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(read_text(dir_ / "stats.json"));
    EXPECT_EQ(stats["spp_reached"], 5);
    EXPECT_EQ(stats["passes"], 3);  // 2 + 2 + 1
    EXPECT_LT(stats["total_seconds"].get<double>(), 10.0) << "the budget is a limit, not a target";
}

TEST_F(RenderOutputs, AdaptiveStatisticsAndSppLayer) {
    write_text(dir_ / "s.json", scene(R"({"width": 32, "height": 24, "spp": 64, "integrator": "path"})"));
    const RunResult r =
        run("render s.json -o out.exr --noise-threshold 0.05 --min-spp 8 --aov spp --quiet "
            "--stats-json stats.json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(read_text(dir_ / "stats.json"));
    EXPECT_EQ(stats["spp"], 64);
    const double reached = stats["spp_reached"].get<double>();
    EXPECT_GT(reached, 8.0);
    EXPECT_LT(reached, 64.0) << "the background (zero variance) stops at the minimum";
    Imf::InputFile file((dir_ / "out.exr").c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    std::vector<float> spp(static_cast<std::size_t>(w * h));
    Imf::FrameBuffer frame;
    frame.insert("spp.Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(spp.data()), sizeof(float),
                                     sizeof(float) * static_cast<std::size_t>(w)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    double sum = 0;
    for (float n : spp) {
        EXPECT_GE(n, 8.0f);
        EXPECT_LE(n, 64.0f);
        sum += n;
    }
    EXPECT_NEAR(sum / (w * h), reached, 1e-6 * reached);
    EXPECT_EQ(spp[0], 8.0f) << "a background corner";
}

TEST_F(RenderOutputs, AovLayersAreNamedAsTheContractSays) {
    write_text(dir_ / "s.json", scene());
    const RunResult r = run("render s.json -o out.exr --spp 1 --aov albedo,normal,depth,position,spp,variance --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    Imf::InputFile file((dir_ / "out.exr").c_str());
    std::set<std::string> names;
    for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c) {
        names.insert(c.name());
        EXPECT_EQ(c.channel().type, Imf::FLOAT) << c.name();
    }
    const std::set<std::string> expected{"R",          "G",          "B",          "albedo.R",   "albedo.G",
                                         "albedo.B",   "normal.X",   "normal.Y",   "normal.Z",   "depth.Z",
                                         "spp.Y",      "position.X", "position.Y", "position.Z", "variance.R",
                                         "variance.G", "variance.B"};
    EXPECT_EQ(names, expected);

    // The square z = 0, seen from (0, 0, 4): the pixel at the image's centre
    // sees it 4 away with albedo 0.5, the corner sees nothing.
    const Imath::Box2i window = file.header().dataWindow();
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    std::vector<std::vector<float>> layers(expected.size(), std::vector<float>(static_cast<std::size_t>(w * h)));
    Imf::FrameBuffer frame;
    std::size_t k = 0;
    std::vector<std::string> order(expected.begin(), expected.end());
    for (const std::string& name : order)
        frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(layers[k++].data()), sizeof(float),
                                      sizeof(float) * static_cast<std::size_t>(w)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    auto value = [&](const std::string& name, int i, int j) {
        const auto at = static_cast<std::size_t>(std::find(order.begin(), order.end(), name) - order.begin());
        return layers[at][static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)];
    };
    ASSERT_EQ(w, 32);
    const int ci = 16, cj = 12;  // its ray passes within a pixel of the axis
    EXPECT_FLOAT_EQ(value("albedo.G", ci, cj), 0.5f);
    EXPECT_NEAR(value("depth.Z", ci, cj), 4.0f, 0.01f);
    EXPECT_NEAR(value("normal.Z", ci, cj), 1.0f, 1e-6f);
    EXPECT_NEAR(value("position.Z", ci, cj), 0.0f, 1e-5f);
    EXPECT_EQ(value("spp.Y", ci, cj), 1.0f);
    EXPECT_EQ(value("variance.G", ci, cj), std::numeric_limits<float>::infinity()) << "one sample: unknown";
    EXPECT_EQ(value("depth.Z", 0, 0), std::numeric_limits<float>::infinity());
    EXPECT_EQ(value("albedo.R", 0, 0), 0.0f);
    EXPECT_GT(value("G", ci, cj), 0.0f);
}

TEST_F(RenderOutputs, CommandLineErrors) {
    write_text(dir_ / "s.json", scene());
    for (const char* args :
         {"--aov albedo -o out.png", "--aov albedo -o out.pfm", "--aov colour -o out.exr", "--aov albedo,, -o out.exr",
          "--time 0", "--time -1", "--time inf", "--time nan", "--time 1e9", "--time soon", "--noise-threshold 0",
          "--noise-threshold -0.1", "--noise-threshold inf", "--min-spp 0", "--min-spp 70000"}) {
        const RunResult r = run(std::string("render s.json ") + args);
        EXPECT_EQ(r.status, 2) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: command line: ", 0), 0u) << args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.png") || fs::exists(dir_ / "out.exr") || fs::exists(dir_ / "out.pfm") ||
                     fs::exists(dir_ / "render.png"))
            << args;
    }
}

}  // namespace
