// The part of a libFuzzer target that only the fuzzer needs: a scratch folder
// for this process, and turning a broken invariant into a crash so that
// libFuzzer saves the input as a reproducer.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz_harness.h"

namespace sombra::fuzz {

// Under $TMPDIR (tools/fuzz.sh points it at /dev/shm), else /dev/shm, else
// the system's temp folder; one per process so parallel jobs never share
// files. Removed when the process exits normally.
struct ScratchFolder {
    fs::path path;

    explicit ScratchFolder(const char* target) {
        fs::path base = fs::temp_directory_path();
        if (!std::getenv("TMPDIR") && fs::is_directory("/dev/shm")) base = "/dev/shm";
        path = base / ("sombra-fuzz-" + std::string(target) + "-" + std::to_string(::getpid()));
        fs::create_directories(path);
    }
    ~ScratchFolder() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
};

// Runs one input; aborts, printing why, when the result breaks an invariant.
inline void run_or_abort(Target target, const char* name, const std::uint8_t* data, std::size_t size) {
    // libFuzzer calls a plain function per input: the folder lives as long as the process.
    static const ScratchFolder folder(name);
    const std::string problem = run_input(target, {reinterpret_cast<const char*>(data), size}, folder.path);
    if (!problem.empty()) {
        std::fprintf(stderr, "sombra fuzz_%s: loaded, but %s\n", name, problem.c_str());
        std::abort();
    }
}

}  // namespace sombra::fuzz
