// Spec §22 from the command line: --frames A-B writes one image a frame,
// each equal bit for bit to --frame F alone (direct and path, instances and
// a keyed camera moving), an animated scene without either renders its
// first frame, --shard I/N with --frames splits frames, and the options'
// misuse is a command-line error.
#include <gtest/gtest.h>

#include <string>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

class AnimationCli : public CliFixture {
protected:
    void SetUp() override {
        CliFixture::SetUp();
        // The square turns about y and rises, twice over (instances), while the camera slides.
        write_text(dir_ / "a.json", R"({
  "render": {"width": 40, "height": 30, "spp": 2},
  "animation": {"fps": 2, "frames": [1, 6]},
  "camera": {"keys": [{"time": 0, "origin": [0, 0, 5], "look_at": [0, 0, 0], "fov": 50},
                      {"time": 3, "origin": [2, 1, 5], "look_at": [0, 0.5, 0], "fov": 40}]},
  "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}},
  "lights": [{"type": "point", "position": [0, 1, 4], "intensity": [9, 9, 9]}],
  "objects": [{"file": "square.obj", "material": "grey",
               "transform": {"keys": [{"time": 0, "transform": [{"scale": 0.5}]},
                                      {"time": 2, "transform": [{"scale": 0.5}, {"rotate": {"axis": [0, 1, 0], "degrees": 80}},
                                                                {"translate": [0, 1, 0]}]}]},
               "instances": [[{"translate": [-1, 0, 0]}], [{"translate": [1, 0, -1]}]]}]})");
    }
};

TEST_F(AnimationCli, EachFrameOfARangeIsThatFrameAlone) {
    for (const std::string integrator : {"direct", "path"}) {
        SCOPED_TRACE(integrator);
        const RunResult all = run("render a.json -q --integrator " + integrator + " --frames 2-5 -o f_###.pfm");
        ASSERT_EQ(all.status, 0) << all.err;
        for (int f = 2; f <= 5; ++f) {
            const RunResult one = run("render a.json -q --threads 1 --integrator " + integrator + " --frame " +
                                      std::to_string(f) + " -o one.pfm");
            ASSERT_EQ(one.status, 0) << one.err;
            EXPECT_EQ(read_text(dir_ / ("f_00" + std::to_string(f) + ".pfm")), read_text(dir_ / "one.pfm")) << f;
        }
        // The frames differ: things move.
        EXPECT_NE(read_text(dir_ / "f_002.pfm"), read_text(dir_ / "f_005.pfm"));
        EXPECT_FALSE(fs::exists(dir_ / "f_001.pfm"));
        EXPECT_FALSE(fs::exists(dir_ / "f_006.pfm"));
    }
}

TEST_F(AnimationCli, WithoutAFrameTheFirstFrameRendersAndStatisticsCountFrames) {
    ASSERT_EQ(run("render a.json -q -o plain.pfm").status, 0);
    ASSERT_EQ(run("render a.json -q --frame 1 -o first.pfm").status, 0);
    EXPECT_EQ(read_text(dir_ / "plain.pfm"), read_text(dir_ / "first.pfm"));
    ASSERT_EQ(run("render a.json -q --frames 0-2 -o g#.png --stats-json s.json").status, 0);
    EXPECT_NE(read_text(dir_ / "s.json").find("\"frames\": 3"), std::string::npos) << read_text(dir_ / "s.json");
    for (const char* name : {"g0.png", "g1.png", "g2.png"}) EXPECT_TRUE(fs::exists(dir_ / name)) << name;
}

TEST_F(AnimationCli, ExplainTellsAFramesStory) {
    const RunResult first = run("explain a.json 20 12 --json --frame 1");
    const RunResult later = run("explain a.json 20 12 --json --frame 5");
    const RunResult plain = run("explain a.json 20 12 --json");
    ASSERT_EQ(first.status, 0) << first.err;
    ASSERT_EQ(later.status, 0) << later.err;
    EXPECT_NE(first.out, later.out);
    EXPECT_EQ(first.out, plain.out) << "without --frame: the scene's first frame";
}

TEST_F(AnimationCli, ShardsSplitFramesWhenFramesAreGiven) {
    for (int i = 0; i < 3; ++i)
        ASSERT_EQ(run("render a.json -q --frames 1-6 --shard " + std::to_string(i) + "/3 -o s_#.pfm").status, 0);
    ASSERT_EQ(run("render a.json -q --frames 1-6 -o w_#.pfm").status, 0);
    for (int f = 1; f <= 6; ++f)
        EXPECT_EQ(read_text(dir_ / ("s_" + std::to_string(f) + ".pfm")),
                  read_text(dir_ / ("w_" + std::to_string(f) + ".pfm")))
            << f;
}

TEST_F(AnimationCli, MisuseIsACommandLineError) {
    const auto expect_usage = [&](const std::string& args, const std::string& fragment) {
        const RunResult r = run(args);
        EXPECT_EQ(r.status, 2) << args << ": " << r.err;
        EXPECT_NE(r.err.find(fragment), std::string::npos) << args << ": " << r.err;
    };
    expect_usage("render a.json --frames 1-3 -o out.png", "--frames needs '#' in the output name");
    expect_usage("render a.json --frames 1-3 --frame 2 -o o#.png", "give --frame or --frames, not both");
    expect_usage("render a.json --frames 3-1 -o o#.png", "expected A-B with 0 <= A <= B");
    expect_usage("render a.json --frames x -o o#.png", "expected A-B");
    expect_usage("render a.json --frame -1 -o o.png", "--frame");
    expect_usage("render a.json --frames 1-3 --time 2 -o o#.png", "--frames and --time cannot go together");
}

TEST_F(AnimationCli, KeysOutOfOrderNameWhereAndWhat) {
    write_text(dir_ / "bad.json", scene(R"({"width": 8, "height": 8})",
                                        R"({"keys": [{"time": 1, "origin": [0, 0, 4], "look_at": [0, 0, 0]},
                                  {"time": 1, "origin": [0, 0, 5], "look_at": [0, 0, 0]}]})"));
    expect_input_error(run("render bad.json -o out.png"), "bad.json: /camera/keys/1/time: key times must increase");
}

}  // namespace
