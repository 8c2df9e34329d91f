// Spec §21's shards from the command line: `render --shard I/N` then
// `merge` gives, bit for bit, the file `render` writes whole (PNG, PFM, EXR
// with AOV layers; direct and path; shards in any order and thread count),
// and merge refuses anything but the N shares of one render.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "cli_test_fixture.h"
#include "image/exr_test_bytes.h"

namespace {

using namespace sombra::cli_test;

class Shards : public CliFixture {
protected:
    // A scene of 71 × 49 pixels (3 × 2 blocks of 32, odd sizes), so that
    // shards own blocks cut by the image's edge too.
    void SetUp() override {
        CliFixture::SetUp();
        write_text(dir_ / "s.json", scene(R"({"width": 71, "height": 49, "spp": 4})"));
    }
    // Renders shard I/N of the scene with `options` into sI.exr.
    void shard(int i, int n, const std::string& options) {
        const RunResult r =
            run("render s.json -q " + options + " --shard " + std::to_string(i) + "/" + std::to_string(n) +
                " --threads " + std::to_string(1 + i % 2) + " -o s" + std::to_string(i) + ".exr");
        ASSERT_EQ(r.status, 0) << r.err;
    }
};

TEST_F(Shards, MergedShardsAreTheWholeRenderBitForBit) {
    for (const std::string options : {"--integrator direct", "--integrator path --aov albedo,depth,spp,variance"}) {
        SCOPED_TRACE(options);
        for (int i = 0; i < 3; ++i) shard(i, 3, options);
        for (const std::string ext : {"exr", "png", "pfm"}) {
            if (ext != "exr" && options.find("--aov") != std::string::npos) continue;  // AOVs need an .exr
            const RunResult whole = run("render s.json -q " + options + " -o whole." + ext);
            ASSERT_EQ(whole.status, 0) << whole.err;
            const RunResult merged = run("merge -q s2.exr s0.exr s1.exr -o merged." + ext);  // any order
            ASSERT_EQ(merged.status, 0) << merged.err;
            EXPECT_EQ(merged.err, "");
            EXPECT_EQ(read_text(dir_ / ("merged." + ext)), read_text(dir_ / ("whole." + ext))) << ext;
        }
        // A shard alone is part of the image: black where the others render.
        EXPECT_NE(read_text(dir_ / "s0.exr"), read_text(dir_ / "whole.exr"));
    }
    // 1, 2 and 7 shards too (7 is more than the image's 6 blocks: one shard has none).
    ASSERT_EQ(run("render s.json -q --integrator path -o whole.pfm").status, 0);
    for (const int n : {1, 2, 7}) {
        std::string parts;
        for (int i = 0; i < n; ++i) {
            shard(i, n, "--integrator path");
            parts += " s" + std::to_string(i) + ".exr";
        }
        const RunResult merged = run("merge -q" + parts + " -o merged.pfm");
        ASSERT_EQ(merged.status, 0) << merged.err;
        EXPECT_EQ(read_text(dir_ / "merged.pfm"), read_text(dir_ / "whole.pfm")) << n << " shards";
    }
}

TEST_F(Shards, MergeRefusesAnythingButTheSharesOfOneRender) {
    for (int i = 0; i < 3; ++i) shard(i, 3, "");
    ASSERT_EQ(run("render s.json -q --shard 1/2 -o half1.exr").status, 0);
    ASSERT_EQ(run("render s.json -q --seed 9 --shard 2/3 -o seed9.exr").status, 0);
    ASSERT_EQ(run("render s.json -q -o plain.exr").status, 0);
    const std::string whole = read_text(dir_ / "s0.exr");
    write_text(dir_ / "cut.exr", whole.substr(0, 400));                  // inside the header
    write_text(dir_ / "short.exr", whole.substr(0, whole.size() - 40));  // inside the pixels

    expect_input_error(run("merge s0.exr s1.exr -o out.png"), "shard 2/3 of this render is missing (2 of 3 given)");
    expect_input_error(run("merge s0.exr s2.exr s2.exr -o out.png"), "shard 2/3 given twice");
    expect_input_error(run("merge s0.exr half1.exr s2.exr -o out.png"), "one of 2 shards, but s0.exr is one of 3");
    expect_input_error(run("merge s0.exr s1.exr seed9.exr -o out.png"),
                       "another render than s0.exr's (seed 9 against seed 0)");
    expect_input_error(run("merge s0.exr plain.exr s2.exr -o out.png"), "plain.exr: not a shard");
    expect_input_error(run("merge cut.exr s1.exr s2.exr -o out.png"), "cut.exr: damaged EXR header");
    expect_input_error(run("merge short.exr s1.exr s2.exr -o out.png"), "short.exr: damaged EXR file: pixel chunk ");
    expect_input_error(run("merge s0.exr missing.exr s2.exr -o out.png"), "missing.exr");
}

// A shard whose line-offset table or chunk sizes claim what the file does not
// hold (OpenEXR would allocate what a chunk claims): one line, nothing written.
TEST_F(Shards, MergeRefusesPixelChunksThatClaimMoreThanTheFile) {
    for (int i = 0; i < 2; ++i) shard(i, 2, "");
    const std::string good = read_text(dir_ / "s0.exr");
    const std::size_t table = sombra::test::exr_header_end(good), chunk0 = sombra::test::exr_chunk(good, 0);
    std::string bytes = good;
    sombra::test::put_le(bytes, chunk0 + 4, 4, 0x7fffffff);  // 2 GiB of pixel data
    write_text(dir_ / "huge.exr", bytes);
    expect_input_error(run("merge huge.exr s1.exr -o out.exr"),
                       "huge.exr: damaged EXR file: pixel chunk 0 claims 2147483647 bytes, more than the", "out.exr");
    bytes = good;
    sombra::test::put_le(bytes, table + 8, 8, std::uint64_t{1} << 40);
    write_text(dir_ / "far.exr", bytes);
    expect_input_error(run("merge s1.exr far.exr -o out.exr"),
                       "far.exr: damaged EXR file: pixel chunk 1 is at byte 1099511627776, outside the pixel data",
                       "out.exr");
}

TEST_F(Shards, ShardOptionsAreCheckedOnTheCommandLine) {
    for (const std::string bad : {"--shard 3/3", "--shard 1", "--shard -1/2", "--shard 1/0", "--shard a/b",
                                  "--shard 0/5000", "--shard 0/2 -o x.png", "--shard 0/2 --noise-threshold 0.1"}) {
        const std::string output = bad.find(" -o ") == std::string::npos ? " -o x.exr" : "";
        const RunResult r = run("render s.json " + bad + output);
        EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: command line: ", 0), 0u) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
    }
}

}  // namespace
