// Spec §27 from the command line: the warnings a new user needs (nothing
// emits light, adaptive sampling that cannot adapt), a folder given as the
// scene, the range of --frame, --tonemap and JPEG output.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli_test_fixture.h"
#include "image/display_transform.h"
#include "image/image_io.h"

namespace {

using namespace sombra::cli_test;

class Everyday : public CliFixture {
protected:
    static std::size_t count(const std::string& text, const std::string& what) {
        std::size_t n = 0;
        for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
        return n;
    }
};

constexpr const char* kNoLight = "nothing in the scene emits light";

TEST_F(Everyday, ASceneWithoutLightRendersBlackWithOneWarning) {
    write_text(dir_ / "dark.json", R"({"render": {"width": 16, "height": 12, "integrator": "path"},
        "camera": {"origin": [0, 0, 4], "look_at": [0, 0, 0]},
        "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}},
        "objects": [{"file": "square.obj", "material": "grey"}]})");
    const RunResult r = run("render dark.json -o dark.pfm -q");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, kNoLight), 1u) << r.err;
    EXPECT_NE(r.err.find("sombra: warning: dark.json: nothing"), std::string::npos) << r.err;
    const Pfm image = read_pfm(dir_ / "dark.pfm");
    ASSERT_EQ(image.rgb.size(), 16u * 12u * 3u);
    EXPECT_TRUE(std::all_of(image.rgb.begin(), image.rgb.end(), [](float v) { return v == 0.0f; }));

    write_text(dir_ / "lit.json", scene());
    const RunResult lit = run("render lit.json -o lit.pfm -q");
    ASSERT_EQ(lit.status, 0) << lit.err;
    EXPECT_EQ(lit.err.find(kNoLight), std::string::npos) << lit.err;
    // A white background lights the scene too.
    write_text(dir_ / "sky.json", R"({"render": {"width": 16, "height": 12}, "background": [1, 1, 1],
        "camera": {"origin": [0, 0, 4], "look_at": [0, 0, 0]}, "objects": [{"file": "square.obj"}]})");
    const RunResult sky = run("render sky.json -o sky.pfm -q");
    ASSERT_EQ(sky.status, 0) << sky.err;
    EXPECT_EQ(sky.err.find(kNoLight), std::string::npos) << sky.err;
}

TEST_F(Everyday, ANoiseThresholdThatCannotStopAnyPixelEarlyWarns) {
    write_text(dir_ / "s.json", scene(R"({"width": 16, "height": 12, "spp": 8, "integrator": "path"})"));
    const RunResult r = run("render s.json -o a.pfm -q --noise-threshold 0.1");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, "--noise-threshold cannot stop any pixel early: --min-spp 16 is not below the 8"), 1u)
        << r.err;
    const RunResult adapts = run("render s.json -o b.pfm -q --noise-threshold 0.1 --min-spp 4");
    ASSERT_EQ(adapts.status, 0) << adapts.err;
    EXPECT_EQ(adapts.err.find("cannot stop"), std::string::npos) << adapts.err;
}

TEST_F(Everyday, AFolderGivenAsTheSceneIsOneLine) {
    fs::create_directories(dir_ / "scenes.json");
    for (const char* folder : {".", "scenes.json"}) {
        const RunResult r = run(std::string("render ") + folder + " -o out.png");
        EXPECT_EQ(r.status, 1);
        EXPECT_EQ(r.err, std::string("sombra: error: ") + folder +
                             ": is a folder, not a scene: give a scene .json or a model file (.obj, .ply, .gltf, "
                             ".glb), e.g. one inside it\n");
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
}

TEST_F(Everyday, FramesRunFromZeroTo2To31Minus1) {
    write_text(dir_ / "s.json", scene());
    const RunResult last = run("render s.json -o last.png -q --frame 2147483647");
    EXPECT_EQ(last.status, 0) << last.err;
    for (const char* frame : {"2147483648", "-1"}) {
        const RunResult r = run(std::string("render s.json -o out.png -q --frame ") + frame);
        EXPECT_EQ(r.status, 2) << frame;
        EXPECT_NE(r.err.find("--frame: must be between 0 and 2147483647"), std::string::npos) << r.err;
    }
    const RunResult frames = run("render s.json -o out_#.png -q --frames 2147483647-2147483648");
    EXPECT_EQ(frames.status, 2) << frames.err;
}

// The 8-bit RGB an image file decodes to (stb_image: PNG or JPEG).
std::vector<unsigned char> decode_rgb(const fs::path& path, int& width, int& height) {
    int channels = 0;
    unsigned char* pixels = stbi_load(path.c_str(), &width, &height, &channels, 3);
    if (pixels == nullptr) return {};
    std::vector<unsigned char> rgb(pixels, pixels + static_cast<std::size_t>(width) * height * 3);
    stbi_image_free(pixels);
    return rgb;
}

TEST_F(Everyday, TheToneMapperShapesEightBitOutputsOnly) {
    write_text(dir_ / "s.json", scene(R"({"width": 16, "height": 12, "spp": 2, "integrator": "path"})"));
    ASSERT_EQ(run("render s.json -o linear.pfm -q").status, 0);
    const Pfm linear = read_pfm(dir_ / "linear.pfm");
    ASSERT_EQ(linear.rgb.size(), 16u * 12u * 3u);
    // PFM rows run bottom to top; the PNG's top to bottom.
    std::vector<float> top_down;
    for (int y = 11; y >= 0; --y)
        top_down.insert(top_down.end(), linear.rgb.begin() + y * 16 * 3, linear.rgb.begin() + (y + 1) * 16 * 3);
    std::vector<std::vector<unsigned char>> shown;
    for (const char* tonemap : {"none", "pbr-neutral"}) {
        const RunResult r = run(std::string("render s.json -o t.png -q --exposure 3 --tonemap ") + tonemap);
        ASSERT_EQ(r.status, 0) << r.err;
        int w = 0, h = 0;
        shown.push_back(decode_rgb(dir_ / "t.png", w, h));
        const std::vector<std::uint8_t> want =
            sombra::display_bytes({16, 12, top_down.data()}, {3.0f, sombra::tonemap_option(tonemap)});
        EXPECT_EQ(shown.back(), std::vector<unsigned char>(want.begin(), want.end())) << tonemap;
    }
    EXPECT_NE(shown[0], shown[1]) << "the exposure should push some pixels into the compression";

    const RunResult jpeg = run("render s.json -o t.jpg -q --tonemap pbr-neutral");
    ASSERT_EQ(jpeg.status, 0) << jpeg.err;
    int w = 0, h = 0;
    EXPECT_EQ(decode_rgb(dir_ / "t.jpg", w, h).size(), 16u * 12u * 3u);
    EXPECT_EQ(read_text(dir_ / "t.jpg").substr(0, 3), "\xFF\xD8\xFF");

    for (const char* out : {"t.exr", "t.pfm"}) {
        const RunResult r = run(std::string("render s.json -q --tonemap pbr-neutral -o ") + out);
        EXPECT_EQ(r.status, 2) << out;
        EXPECT_NE(r.err.find("--tonemap applies to 8-bit outputs (.png, .jpg)"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / out));
    }
    const RunResult unknown = run("render s.json -q --tonemap aces -o t.png");
    EXPECT_EQ(unknown.status, 2);
    EXPECT_NE(unknown.err.find("--tonemap: expected none or pbr-neutral, not 'aces'"), std::string::npos)
        << unknown.err;
    ASSERT_EQ(run("render s.json -q --shard 0/1 -o part.exr").status, 0);
    EXPECT_EQ(run("merge part.exr -q --tonemap pbr-neutral -o merged.exr").status, 2);
    EXPECT_EQ(run("merge part.exr -q --tonemap pbr-neutral -o merged.jpg").status, 0);
}

// Pixels x0 … x1 − 1 of rows y0 … y1 − 1 of a width-wide PFM's floats, top row first.
std::vector<float> window_of(const Pfm& image, int x0, int y0, int x1, int y1) {
    std::vector<float> out;
    for (int y = y0; y < y1; ++y) {
        // PFM rows run bottom to top.
        const std::size_t row = static_cast<std::size_t>(image.height - 1 - y) * image.width;
        out.insert(out.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>((row + x0) * 3),
                   image.rgb.begin() + static_cast<std::ptrdiff_t>((row + x1) * 3));
    }
    return out;
}

std::vector<float> top_down(const Pfm& image) { return window_of(image, 0, 0, image.width, image.height); }

TEST_F(Everyday, ACropIsItsWindowOfTheWholeRenderBitForBit) {
    write_text(dir_ / "s.json", scene(R"({"width": 45, "height": 31, "spp": 24, "integrator": "path"})"));
    struct Case {
        std::string options;
        bool adapts;
    };
    for (const Case& c : {Case{"", false}, Case{"--noise-threshold 0.08 --min-spp 4", true}}) {
        SCOPED_TRACE(c.options);
        ASSERT_EQ(run("render s.json -q -o whole.pfm --stats-json whole.json " + c.options).status, 0);
        const RunResult r = run("render s.json -q -o crop.pfm --stats-json crop.json --crop 3 5 40 29 " + c.options);
        ASSERT_EQ(r.status, 0) << r.err;
        const Pfm whole = read_pfm(dir_ / "whole.pfm"), crop = read_pfm(dir_ / "crop.pfm");
        ASSERT_EQ(crop.width, 37);
        ASSERT_EQ(crop.height, 24);
        EXPECT_EQ(top_down(crop), window_of(whole, 3, 5, 40, 29));
        const auto stats = nlohmann::json::parse(read_text(dir_ / "crop.json"));
        EXPECT_EQ(stats["width"], 37);
        EXPECT_EQ(stats["height"], 24);
        // Adaptive sampling stopped some pixels early (the spp reached is a
        // mean, not a whole number): the margin mattered.
        const auto whole_stats = nlohmann::json::parse(read_text(dir_ / "whole.json"));
        EXPECT_EQ(whole_stats["spp_reached"].is_number_integer(), !c.adapts) << whole_stats.dump();
    }
    // Shards split the window; merged, they are the crop.
    ASSERT_EQ(run("render s.json -q -o crop.pfm --crop 3 5 40 29").status, 0);
    for (const char* part : {"0/3", "1/3", "2/3"}) {
        const RunResult r =
            run(std::string("render s.json -q --crop 3 5 40 29 --shard ") + part + " -o part" + part[0] + ".exr");
        ASSERT_EQ(r.status, 0) << r.err;
    }
    const RunResult merged = run("merge part0.exr part1.exr part2.exr -q -o merged.pfm");
    ASSERT_EQ(merged.status, 0) << merged.err;
    EXPECT_EQ(read_text(dir_ / "merged.pfm"), read_text(dir_ / "crop.pfm"));
    // A shard of another window does not merge with them.
    ASSERT_EQ(run("render s.json -q --crop 3 5 40 30 --shard 2/3 -o other.exr").status, 0);
    EXPECT_EQ(run("merge part0.exr part1.exr other.exr -q -o merged.pfm").status, 1);
}

TEST_F(Everyday, ADenoisedCropIsItsWindowOfTheWholeDenoisedRender) {
    // Wide enough that the window grown by the denoiser's reach is not the image.
    write_text(dir_ / "s.json", scene(R"({"width": 200, "height": 130, "spp": 4, "integrator": "path"})"));
    for (const std::string options : {"", " --noise-threshold 0.2 --min-spp 2 --spp 6"}) {
        SCOPED_TRACE(options);
        ASSERT_EQ(run("render s.json -q --denoise --aov noisy -o whole.exr" + options).status, 0);
        const RunResult r = run("render s.json -q --denoise --aov noisy -o crop.exr --crop 131 90 171 121" + options);
        ASSERT_EQ(r.status, 0) << r.err;
        ASSERT_EQ(run("render s.json -q --denoise -o whole.pfm" + options).status, 0);
        ASSERT_EQ(run("render s.json -q --denoise -o crop.pfm --crop 131 90 171 121" + options).status, 0);
        const Pfm whole = read_pfm(dir_ / "whole.pfm"), crop = read_pfm(dir_ / "crop.pfm");
        ASSERT_EQ(crop.width, 40);
        ASSERT_EQ(crop.height, 31);
        EXPECT_EQ(top_down(crop), window_of(whole, 131, 90, 171, 121));
        // The noisy layer is the crop's too.
        const auto noisy_red = [this](const char* file, int x0, int y0, int width) {
            const sombra::ExrChannels exr = sombra::read_exr_channels(dir_ / file, {"noisy.R"});
            std::vector<float> out;
            if (exr.values.size() != 1) return out;
            for (int y = y0; y < y0 + 31; ++y)
                for (int x = x0; x < x0 + 40; ++x)
                    out.push_back(exr.values[0][static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                                static_cast<std::size_t>(x)]);
            return out;
        };
        EXPECT_EQ(noisy_red("crop.exr", 0, 0, 40), noisy_red("whole.exr", 131, 90, 200));
    }
}

TEST_F(Everyday, ADenoisedCropSplitIntoShardsMergesToTheDenoisedCrop) {
    write_text(dir_ / "s.json", scene(R"({"width": 200, "height": 130, "spp": 4, "integrator": "path"})"));
    const std::string crop = " --crop 131 90 171 121";
    ASSERT_EQ(run("render s.json -q --denoise -o denoised.pfm" + crop).status, 0);
    ASSERT_EQ(run("render s.json -q -o noisy.pfm" + crop).status, 0);
    // The shards split the window grown by the denoiser's 54-pixel reach,
    // its corner moved back to a multiple of 64: x 64 to 200, y 0 to 130;
    // and they say where the crop lies in it.
    for (const char* part : {"0/2", "1/2"}) {
        const RunResult r =
            run(std::string("render s.json -q --denoise --shard ") + part + " -o part" + part[0] + ".exr" + crop);
        ASSERT_EQ(r.status, 0) << r.err;
    }
    const sombra::ExrChannels part = sombra::read_exr_channels(dir_ / "part0.exr", {"R"});
    EXPECT_EQ(part.width, 200 - 64);
    EXPECT_EQ(part.height, 130);
    const auto kept = std::find_if(part.attributes.begin(), part.attributes.end(),
                                   [](const sombra::ImageAttribute& a) { return a.name == "sombra.kept"; });
    ASSERT_NE(kept, part.attributes.end());
    EXPECT_EQ(kept->value, "67 90 40 31");

    RunResult merged = run("merge part0.exr part1.exr -q --denoise -o merged.pfm");
    ASSERT_EQ(merged.status, 0) << merged.err;
    EXPECT_EQ(read_text(dir_ / "merged.pfm"), read_text(dir_ / "denoised.pfm"));
    // Merged without denoising: the noisy crop.
    merged = run("merge part0.exr part1.exr -q -o merged-noisy.pfm");
    ASSERT_EQ(merged.status, 0) << merged.err;
    EXPECT_EQ(read_text(dir_ / "merged-noisy.pfm"), read_text(dir_ / "noisy.pfm"));
    // A shard that keeps another window does not merge with them.
    ASSERT_EQ(run("render s.json -q --denoise --shard 1/2 -o other.exr --crop 131 90 171 120").status, 0);
    merged = run("merge part0.exr other.exr -q --denoise -o x.pfm");
    EXPECT_EQ(merged.status, 1);
    EXPECT_FALSE(fs::exists(dir_ / "x.pfm"));
    // Nor one whose attribute is damaged (edited in place: same length, a valid EXR).
    const std::string bytes = read_text(dir_ / "part1.exr");
    const std::size_t at = bytes.find("67 90 40 31");
    ASSERT_NE(at, std::string::npos);
    for (const auto& [text, message] :
         {std::pair{"67 90 99 31", "sombra.kept '67 90 99 31' is not a window of its 136x130 pixels"},
          std::pair{"67 90 4x 31", "unreadable sombra.kept '67 90 4x 31'"}}) {
        write_text(dir_ / "bad.exr", std::string(bytes).replace(at, 11, text));
        merged = run("merge part0.exr bad.exr -q --denoise -o x.pfm");
        EXPECT_EQ(merged.status, 1);
        EXPECT_EQ(merged.err, std::string("sombra: error: bad.exr: damaged shard: ") + message + "\n");
        EXPECT_FALSE(fs::exists(dir_ / "x.pfm"));
    }
}

TEST_F(Everyday, ACropOutsideTheImageIsRefused) {
    write_text(dir_ / "s.json", scene());  // 32 × 24
    const RunResult outside = run("render s.json -q -o a.png --crop 0 0 33 10");
    EXPECT_EQ(outside.status, 1);
    EXPECT_EQ(outside.err,
              "sombra: error: --crop: expected X0 Y0 X1 Y1 with 0 <= X0 < X1 <= 32 and 0 <= Y0 < Y1 <= 24 (the image), "
              "not 0 0 33 10\n");
    EXPECT_FALSE(fs::exists(dir_ / "a.png"));
    for (const char* bad : {"--crop 5 5 5 9", "--crop 1 2 3"}) {
        const RunResult r = run(std::string("render s.json -q -o a.png ") + bad);
        EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
    }
}

TEST_F(Everyday, AMisspeltOptionOrAMissingCommandIsNamedWithTheLikelyFix) {
    write_text(dir_ / "s.json", scene());
    struct Case {
        const char* args;
        const char* message;
    };
    for (const Case& c : {Case{"render s.json --widht 100",
                               "unknown option '--widht' (did you mean --width?) (see 'sombra render --help')"},
                          Case{"render s.json --noise-treshold=0.1",
                               "unknown option '--noise-treshold' (did you mean --noise-threshold?)"},
                          Case{"explain s.json 1 2 --smaple 3", "unknown option '--smaple' (did you mean --sample?)"},
                          Case{"render s.json --zzzzzzzz", "unknown option '--zzzzzzzz' (see"},
                          Case{"s.json",
                               "'s.json' is not a command: to render it, run 'sombra render s.json' (commands: render, "
                               "explain, view, merge, denoise)"},
                          Case{"rendr s.json", "unknown command 'rendr' (did you mean render?)"}}) {
        const RunResult r = run(c.args);
        EXPECT_EQ(r.status, 2) << c.args;
        EXPECT_EQ(r.err.rfind(std::string("sombra: error: command line: ") + c.message, 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

TEST_F(Everyday, AMissingMeshSaysWhereItWasSought) {
    fs::create_directories(dir_ / "scenes");
    write_text(dir_ / "scenes" / "s.json", R"({"camera": {"origin": [0, 0, 3], "look_at": [0, 0, 0]},
        "objects": [{"file": "models/sphere.obj"}]})");
    const RunResult r = run("render scenes/s.json -o out.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err,
              "sombra: error: scenes/s.json: /objects/0/file: cannot open 'models/sphere.obj': no such file "
              "(looked for " +
                  (fs::canonical(dir_) / "scenes" / "models" / "sphere.obj").string() +
                  ", relative to the scene's folder)\n");
}

}  // namespace
