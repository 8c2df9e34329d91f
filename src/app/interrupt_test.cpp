// Ctrl-C and kill during a render: a prompt stop, no output, and an earlier
// image left exactly as it was.
#include <gtest/gtest.h>
#include <signal.h>  // NOLINT(modernize-deprecated-headers): kill() is POSIX, declared here, not in <csignal>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "cli_test_fixture.h"

namespace {

namespace fs = std::filesystem;
using sombra::cli_test::read_text;

class Interrupt : public ::testing::TestWithParam<int> {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("sombra-interrupt-" + std::to_string(::getpid()) + "-" + std::to_string(GetParam()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        std::ofstream(dir_ / "square.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
        // Thousands of samples per pixel: far longer than the test waits.
        std::ofstream(dir_ / "slow.json") << R"({"render": {"width": 256, "height": 256, "spp": 20000},
            "camera": {"origin": [0, 0, 3], "look_at": [0, 0, 0]},
            "lights": [{"type": "point", "position": [0, 0, 2], "intensity": [1, 1, 1]}],
            "objects": [{"file": "square.obj"}]})";
        std::ofstream(dir_ / "out.png") << "earlier image";
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

TEST_P(Interrupt, StopsWithinASecondAndWritesNothing) {
    const int sig = GetParam();
    const fs::path err = dir_ / "stderr.txt";
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        if (chdir(dir_.c_str()) != 0) _exit(99);
        if (!freopen(err.c_str(), "w", stderr)) _exit(99);
        execl(SOMBRA_EXE, SOMBRA_EXE, "render", "slow.json", "-o", "out.png", "--quiet", static_cast<char*>(nullptr));
        _exit(98);
    }
    // Let it load and start rendering.
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    const auto sent = std::chrono::steady_clock::now();
    ASSERT_EQ(kill(pid, sig), 0);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();

    EXPECT_LT(seconds, 1.0);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping cleanly";
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    const std::string message = read_text(err);
    EXPECT_EQ(message.rfind("sombra: error: SIG", 0), 0u) << message;
    EXPECT_NE(message.find("interrupted"), std::string::npos) << message;
    EXPECT_EQ(read_text(dir_ / "out.png"), "earlier image");
    for (const auto& entry : fs::directory_iterator(dir_))
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupt, ::testing::Values(SIGINT, SIGTERM));

}  // namespace
