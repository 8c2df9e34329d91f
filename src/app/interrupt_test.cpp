// Ctrl-C and kill during a render: a prompt stop, no output, and an earlier
// image left exactly as it was.
#include <gtest/gtest.h>
#include <signal.h>  // NOLINT(modernize-deprecated-headers): kill() is POSIX, declared here, not in <csignal>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <regex>
#include <vector>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "cli_test_fixture.h"
#include "view/view_test_util.h"

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

TEST_P(Interrupt, EndsTheViewerAtOnceWhateverItsClientsDo) {
    // Spec §20: Ctrl-C ends the server at once, even with event streams and
    // an image download that their clients stopped reading (still open).
    const int sig = GetParam();
    int out[2];
    ASSERT_EQ(::pipe(out), 0);
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        if (chdir(dir_.c_str()) != 0) _exit(99);
        ::dup2(out[1], STDOUT_FILENO);
        ::close(out[0]);
        if (!freopen("stderr.txt", "w", stderr)) _exit(99);
        execl(SOMBRA_EXE, SOMBRA_EXE, "view", "slow.json", "--port", "0", "--width", "1024", "--height", "1024",
              static_cast<char*>(nullptr));
        _exit(98);
    }
    ::close(out[1]);
    // The first line: http://127.0.0.1:PORT/?token=TOKEN
    std::string line;
    char c = 0;
    while (::read(out[0], &c, 1) == 1 && c != '\n') line += c;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(line, m, std::regex(R"(127\.0\.0\.1:(\d+)/\?token=(\w+))"))) << line;
    const int port = std::stoi(m[1].str());
    const std::string token = m[2].str();
    std::vector<int> stalled;
    for (const char* path : {"/events", "/events", "/image.exr"})
        stalled.push_back(sombra::view_test::open_unread_stream(port, std::string(path) + "?token=" + token));
    for (const int fd : stalled) EXPECT_GE(fd, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(700));  // the streams and the download under way

    const auto sent = std::chrono::steady_clock::now();
    ASSERT_EQ(kill(pid, sig), 0);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    EXPECT_LT(seconds, 1.0);  // httplib's write and keep-alive timeouts are 5 s
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_NE(read_text(dir_ / "stderr.txt").find("sombra: view ended"), std::string::npos);
    for (const int fd : stalled)
        if (fd >= 0) ::close(fd);
    ::close(out[0]);
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupt, ::testing::Values(SIGINT, SIGTERM));

}  // namespace
