// What the command-line tests share: running the real executable in a fresh
// temp folder, under a time limit and (unless built with sanitizers, which
// reserve terabytes of address space) a memory limit, and checking the
// contract for a bad input: exit 1, one line "sombra: error: WHERE: WHAT",
// no image and no temporary file left behind.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace sombra::cli_test {

namespace fs = std::filesystem;

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

// Address space a run may use by default, in KiB: 4 GiB holds the largest
// image the limits allow (2^28 pixels, 3 GiB of film) and any honest test
// scene, plus room for each hardware thread's stack and malloc arena.
inline long default_memory_kib() { return (4L << 20) + long(std::thread::hardware_concurrency()) * (128L << 10); }
// Every bad input must end within seconds; a hang fails the test instead of stalling it.
inline constexpr int kTimeoutSeconds = 20;

struct RunResult {
    int status = -1;  // exit status; 124 when the time limit stopped it
    std::string out, err;
    double seconds = 0;  // wall time of the whole command
};

inline std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// `text` as one word for /bin/sh, whatever bytes it holds.
inline std::string shell_quote(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

struct Pfm {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

// Reads the little-endian PFM sombra writes ("PF\nW H\n-1.0\n" + floats, rows
// bottom to top); empty when the file is not one.
inline Pfm read_pfm(const fs::path& path) {
    const std::string bytes = read_text(path);
    Pfm image;
    std::istringstream header(bytes);
    std::string magic, scale;
    header >> magic >> image.width >> image.height >> scale;
    const std::size_t floats = std::size_t(std::max(image.width, 0)) * std::size_t(std::max(image.height, 0)) * 3;
    const std::size_t data = static_cast<std::size_t>(header.tellg()) + 1;
    if (magic != "PF" || bytes.size() != data + floats * 4) return {};
    image.rgb.resize(floats);
    std::memcpy(image.rgb.data(), bytes.data() + data, floats * 4);
    return image;
}

class CliFixture : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("sombra-cli-" + std::to_string(::getpid()) + "-" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        // A unit square facing +z, and a scene that frames it.
        write_text(dir_ / "square.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Runs sombra with `args` (already shell-quoted) in the temp folder, with
    // kTimeoutSeconds of time and at most `memory_kib` of address space
    // (0: default_memory_kib(); a run given less should use few threads),
    // `env` ("NAME=VALUE ...") added to its environment.
    RunResult run(const std::string& args, long memory_kib = 0, const std::string& env = "") {
        if (memory_kib == 0) memory_kib = default_memory_kib();
        std::string cmd = "cd " + shell_quote(dir_.string()) + " && ";
        if (!kSanitized) cmd += "ulimit -v " + std::to_string(memory_kib) + " && ";
        cmd += "exec " + (env.empty() ? std::string() : "env " + env + " ") + "timeout -k 5 " +
               std::to_string(kTimeoutSeconds) + " " + shell_quote(SOMBRA_EXE) + " " + args;
        return run_shell(cmd);
    }

    // Runs the shell command `cmd` with its output captured and no input:
    // its exit status, stdout, stderr and wall time.
    RunResult run_shell(const std::string& cmd) {
        const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
        const std::string full =
            cmd + " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string()) + " </dev/null";
        const auto start = std::chrono::steady_clock::now();
        const int raw = std::system(full.c_str());
        RunResult r;
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
        r.out = read_text(out);
        r.err = read_text(err);
        fs::remove(out);
        fs::remove(err);
        return r;
    }

    std::string scene(const std::string& render = R"({"width": 32, "height": 24})",
                      const std::string& camera = R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})",
                      const std::string& extra = "", const std::string& mesh = "square.obj") {
        return R"({"render": )" + render + R"(, "camera": )" + camera +
               R"(, "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}},
                 "lights": [{"type": "point", "position": [0, 0, 3], "intensity": [5, 5, 5]}],
                 "objects": [{"file": ")" +
               mesh + R"(", "material": "grey"}])" + extra + "}";
    }

    // No temporary image file anywhere under the temp folder.
    void expect_no_temp_files() {
        for (const auto& entry : fs::recursive_directory_iterator(dir_))
            EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
    }

    // The contract for every bad input: exit 1, one line "sombra: error: WHERE: WHAT"
    // containing `fragment`, no image at `output` (relative to the temp folder), no temporary file.
    void expect_input_error(const RunResult& r, const std::string& fragment, const fs::path& output = "out.png") {
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << r.err;
        EXPECT_NE(r.err.find(fragment), std::string::npos) << "expected '" << fragment << "' in: " << r.err;
        EXPECT_FALSE(fs::exists(dir_ / output));
        expect_no_temp_files();
    }

    fs::path dir_;
};

}  // namespace sombra::cli_test
