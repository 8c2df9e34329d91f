// Spec §21's MPI: `mpirun -np K sombra render` writes the bytes one process
// writes (PNG, PFM, EXR with AOVs; direct and path; odd sizes), its stats say
// `processes`, a rank killed mid-render ends the job with exit ≠ 0 and no
// file, and the binary without mpirun never starts MPI. Skipped when there
// is no mpirun or the build has no MPI, unless SOMBRA_REQUIRE_MPI is set.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

bool mpi_required() { return std::getenv("SOMBRA_REQUIRE_MPI") != nullptr; }

class Mpi : public CliFixture {
protected:
    void SetUp() override {
        CliFixture::SetUp();
#ifndef SOMBRA_TEST_HAVE_MPI
        if (mpi_required()) FAIL() << "SOMBRA_REQUIRE_MPI is set, but sombra was built without MPI";
        GTEST_SKIP() << "sombra was built without MPI (no Open MPI found): MPI tests skipped";
#endif
        // Open MPI is not built with the sanitizers and leaks at exit by
        // design: these tests run in the release suite (tools/test.sh, which
        // CI runs with SOMBRA_REQUIRE_MPI), not under ASan.
        if (kSanitized) GTEST_SKIP() << "MPI tests run in the release build, not under the sanitizers";
        if (std::system("command -v mpirun >/dev/null 2>&1") != 0) {
            if (mpi_required()) FAIL() << "SOMBRA_REQUIRE_MPI is set, but there is no mpirun";
            GTEST_SKIP() << "no mpirun on PATH: MPI tests skipped";
        }
        // 71 × 49: 3 × 2 blocks, cut by the image's edges.
        write_text(dir_ / "s.json", scene(R"({"width": 71, "height": 49, "spp": 4})"));
    }

    // `sombra ARGS` under mpirun with `ranks` processes and the environment
    // words `env` ("NAME=VALUE ..."); as root (CI), in a container without
    // ptrace, and (under ASan) not counting Open MPI's own leaks at exit.
    RunResult mpirun(int ranks, const std::string& args, const std::string& env = "") {
        return run_shell("cd " + shell_quote(dir_.string()) +
                         " && OMPI_MCA_btl_vader_single_copy_mechanism=none ASAN_OPTIONS=detect_leaks=0 " + env +
                         " timeout -k 5 60 mpirun --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) +
                         " " + shell_quote(SOMBRA_EXE) + " " + args);
    }
    // How many times `part` occurs in `text`.
    static std::size_t count(const std::string& text, const std::string& part) {
        std::size_t n = 0;
        for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
        return n;
    }
};

TEST_F(Mpi, RanksWriteTheSingleProcessBytes) {
    struct Case {
        int ranks;
        std::string options, file;
    };
    for (const Case& c : {Case{2, "--integrator direct", "out.png"}, Case{3, "--integrator path", "out.pfm"},
                          Case{4, "--integrator path --aov albedo,normal,depth,spp,variance", "out.exr"},
                          Case{2, "--integrator path --spp 3 --threads 1", "out.exr"},
                          Case{3, "--integrator path --crop 7 5 61 44 --aov albedo,spp", "crop.exr"},
                          Case{3, "--integrator path --denoise --aov noisy,denoise", "denoised.exr"}}) {
        SCOPED_TRACE(std::to_string(c.ranks) + " ranks, " + c.options + ", " + c.file);
        const RunResult single = run("render s.json -q " + c.options + " -o single-" + c.file);
        ASSERT_EQ(single.status, 0) << single.err;
        const RunResult ranks = mpirun(c.ranks, "render s.json -q " + c.options + " -o " + c.file);
        ASSERT_EQ(ranks.status, 0) << ranks.err;
        EXPECT_EQ(ranks.err, "");
        EXPECT_EQ(read_text(dir_ / c.file), read_text(dir_ / ("single-" + c.file)));
    }
}

TEST_F(Mpi, TheSummaryIsOneLineAndNamesTheRanks) {
    const RunResult r = mpirun(2, "render s.json --integrator path --threads 1 -o two.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.err, "sombra: "), 1u) << r.err;
    EXPECT_NE(r.err.find("2 processes × 1 thread each)"), std::string::npos) << r.err;
}

TEST_F(Mpi, StatsSayProcessesAndCountRaysOverAllRanks) {
    ASSERT_EQ(run("render s.json -q --integrator path --stats-json one.json -o one.png").status, 0);
    const RunResult r = mpirun(3, "render s.json -q --integrator path --stats-json three.json -o three.png");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto one = nlohmann::json::parse(read_text(dir_ / "one.json"));
    const auto three = nlohmann::json::parse(read_text(dir_ / "three.json"));
    EXPECT_EQ(one["processes"], 1);
    EXPECT_EQ(three["processes"], 3);
    for (const char* count : {"camera_rays", "shadow_rays", "bounce_rays"})
        EXPECT_EQ(three[count], one[count]) << count;
}

TEST_F(Mpi, FramesSpreadOverRanksEqualOneProcess) {
    ASSERT_EQ(run("render s.json -q --frames 0-4 --stats-json one.json -o one_##.png").status, 0);
    const RunResult r = mpirun(2, "render s.json -q --frames 0-4 --stats-json two.json -o two_##.png");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const std::string n : {"00", "01", "02", "03", "04"})
        EXPECT_EQ(read_text(dir_ / ("two_" + n + ".png")), read_text(dir_ / ("one_" + n + ".png"))) << n;
    const auto one = nlohmann::json::parse(read_text(dir_ / "one.json"));
    const auto two = nlohmann::json::parse(read_text(dir_ / "two.json"));
    EXPECT_EQ(two["frames"], 5);
    EXPECT_EQ(two["processes"], 2);
    EXPECT_EQ(two["camera_rays"], one["camera_rays"]);
}

TEST_F(Mpi, AKilledRankEndsTheJobWithNoImage) {
    // 256 blocks: rank 1 gets some before rank 0 alone could render them all.
    write_text(dir_ / "big.json", scene(R"({"width": 512, "height": 512, "spp": 32, "integrator": "path"})"));
    const RunResult r = mpirun(2, "render big.json -q -o out.png", "SOMBRA_TEST_KILL_RANK=1");
    EXPECT_NE(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("exited on signal 9"), std::string::npos) << r.err;  // mpirun's word for the kill
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    expect_no_temp_files();
}

TEST_F(Mpi, AFailingInputEndsEveryRankWithOneLine) {
    const RunResult r = mpirun(2, "render missing.json -q -o out.png");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("sombra: error: missing.json"), std::string::npos) << r.err;
    EXPECT_EQ(count(r.err, "sombra: "), 1u) << r.err;  // not rank 1's too, nor its SIGTERM
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

TEST_F(Mpi, OptionsThatCannotBeSplitAreRefused) {
    for (const std::string options :
         {"--time 1 -o out.png", "--noise-threshold 0.1 -o out.png", "--shard 0/2 -o out.exr"}) {
        const RunResult r = mpirun(2, "render s.json -q " + options);
        EXPECT_NE(r.status, 0) << options;
        EXPECT_NE(r.err.find("sombra: error: command line: "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("mpirun"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.png") || fs::exists(dir_ / "out.exr"));
    }
}

TEST_F(Mpi, WithoutItsPluginMpirunIsRefusedInOneLine) {
    // The MPI plugin (libsombra_mpi.so, the sombra-mpi package) is missing:
    // mpirun's ranks refuse, rank 0 says why, and a plain run is unaffected.
    const RunResult r = mpirun(2, "render s.json -q -o out.png", "SOMBRA_PLUGIN_DIR=/nonexistent");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("sombra: error: command line: this sombra cannot run under mpirun: its MPI plugin "
                         "libsombra_mpi.so is not in /nonexistent (install the sombra-mpi package"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    EXPECT_EQ(run("render s.json -q -o out.png", 0, "SOMBRA_PLUGIN_DIR=/nonexistent").status, 0);
}

TEST_F(Mpi, WithoutALauncherNoMpiStarts) {
    // An Open MPI that had to start would fail with this (MPI_Init aborts on
    // an unknown component), so a run that succeeds never called it.
    ASSERT_EQ(run("render s.json -q -o plain.png").status, 0);
    for (const std::string env : {"OMPI_MCA_pml=none-such", "OMPI_MCA_pml=none-such OMPI_COMM_WORLD_SIZE=1"}) {
        const RunResult r = run("render s.json -q --stats-json stats.json -o out.png", 0, env);
        ASSERT_EQ(r.status, 0) << env << ": " << r.err;
        EXPECT_EQ(read_text(dir_ / "out.png"), read_text(dir_ / "plain.png"));
        EXPECT_EQ(nlohmann::json::parse(read_text(dir_ / "stats.json"))["processes"], 1);
    }
}

}  // namespace
