#include "io/vdb/isolated_read.h"

#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <exception>

#include "core/error.h"
#include "io/vdb/vdb_reader.h"

// A sanitizer runtime's hook (weak: absent from plain builds). The child
// clears it so that a fuzzer's crash handler, inherited through fork, does
// not take the child's death for the fuzzer's own.
extern "C" void __sanitizer_set_death_callback(  // NOLINT(bugprone-reserved-identifier): its name
    void (*callback)()) __attribute__((weak));

namespace sombra {

namespace {

constexpr std::uint32_t kMagic = 0x56444253;  // "SBDV"
constexpr std::size_t kMaxMessage = 4096;

// What the child sends before the values (or an error's text).
struct Header {
    std::uint32_t magic = kMagic;
    std::uint32_t ok = 0;
    std::array<std::int32_t, 3> dims{};
    std::array<std::int32_t, 3> origin{};
    std::array<float, 12> transform{};
    std::uint64_t message_bytes = 0;
    std::uint64_t value_count = 0;
};

bool write_all(int fd, const void* data, std::size_t bytes) {
    const char* p = static_cast<const char*>(data);
    while (bytes > 0) {
        const ssize_t n = ::write(fd, p, bytes);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        bytes -= static_cast<std::size_t>(n);
    }
    return true;
}

// Reads exactly `bytes`, waiting until `deadline` at most; false on EOF, error or time out.
bool read_all(int fd, void* data, std::size_t bytes, std::chrono::steady_clock::time_point deadline) {
    char* p = static_cast<char*>(data);
    while (bytes > 0) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return false;
        pollfd pfd{fd, POLLIN, 0};
        const int ready = ::poll(&pfd, 1, static_cast<int>(std::min<std::int64_t>(left.count(), 1000)));
        if (ready < 0 && errno == EINTR) continue;
        if (ready < 0) return false;
        if (ready == 0) continue;
        const ssize_t n = ::read(fd, p, bytes);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        bytes -= static_cast<std::size_t>(n);
    }
    return true;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

// The child: read, send, and leave without running the parent's exit handlers.
[[noreturn]] void child(int fd, std::uintmax_t file_bytes, const std::function<DensityGrid()>& read) {
    if (__sanitizer_set_death_callback != nullptr) __sanitizer_set_death_callback(nullptr);
    // The heap a file may make the library claim: enough for the largest
    // dense box and a tree several times the file, not what a forged count
    // asks. (Not under AddressSanitizer, whose shadow memory counts too.)
    if (!kAddressSanitizer) {
        const rlim_t limit = (rlim_t{2} << 30) + 8 * static_cast<rlim_t>(file_bytes);
        const rlimit r{limit, limit};
        ::setrlimit(RLIMIT_DATA, &r);
    }
    Header h;
    std::string message;
    DensityGrid grid;
    try {
        grid = read();
        h.ok = 1;
    } catch (const Error& e) {
        message = e.message();
    } catch (const std::bad_alloc&) {
        message = "not a readable OpenVDB file (it asks for more memory than sombra lets it have)";
    } catch (const std::exception& e) {
        message = std::string("not a readable OpenVDB file (") + e.what() + ")";
    } catch (...) {
        message = "not a readable OpenVDB file";
    }
    if (message.size() > kMaxMessage) message.resize(kMaxMessage);
    if (h.ok) {
        for (std::size_t a = 0; a < 3; ++a) {
            h.dims[a] = grid.dims[a];
            h.origin[a] = grid.origin[a];
        }
        std::memcpy(h.transform.data(), grid.index_to_world.m.data(), sizeof h.transform);
        h.value_count = grid.values.size();
    }
    h.message_bytes = message.size();
    const bool sent = write_all(fd, &h, sizeof h) && write_all(fd, message.data(), message.size()) &&
                      write_all(fd, grid.values.data(), grid.values.size() * sizeof(float));
    ::_exit(sent ? 0 : 1);
}

}  // namespace

DensityGrid read_isolated(const std::string& name, std::uintmax_t file_bytes,
                          const std::function<DensityGrid()>& read) {
    int fds[2];
    if (::pipe(fds) != 0) return read();
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        return read();
    }
    if (pid == 0) {
        ::close(fds[0]);
        child(fds[1], file_bytes, read);
    }
    ::close(fds[1]);
    // Ten seconds, and one more for every 20 MB: far more than reading takes.
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::seconds(10 + static_cast<std::int64_t>(file_bytes / 20'000'000));
    Header h;
    std::string failure;
    DensityGrid grid;
    if (!read_all(fds[0], &h, sizeof h, deadline) || h.magic != kMagic) {
        failure = "the OpenVDB reader stopped before it finished";
    } else if (!h.ok) {
        failure.resize(std::min<std::uint64_t>(h.message_bytes, kMaxMessage));
        if (!read_all(fds[0], failure.data(), failure.size(), deadline) || failure.empty())
            failure = "not a readable OpenVDB file";
    } else {
        std::uint64_t voxels = 1;
        bool sane = true;
        for (std::size_t a = 0; a < 3; ++a) {
            sane = sane && h.dims[a] >= 2;
            if (sane) voxels *= static_cast<std::uint64_t>(h.dims[a]);
            sane = sane && voxels <= kMaxDenseVoxels;
        }
        if (!sane || voxels != h.value_count) {
            failure = "the OpenVDB reader sent a grid of the wrong size";
        } else {
            for (std::size_t a = 0; a < 3; ++a) {
                grid.dims[a] = h.dims[a];
                grid.origin[a] = h.origin[a];
            }
            std::memcpy(grid.index_to_world.m.data(), h.transform.data(), sizeof h.transform);
            grid.values.resize(voxels);
            if (!read_all(fds[0], grid.values.data(), voxels * sizeof(float), deadline))
                failure = "the OpenVDB reader stopped before it finished";
        }
    }
    ::close(fds[0]);
    int status = 0;
    if (!failure.empty()) ::kill(pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (failure.empty() && !(WIFEXITED(status) && WEXITSTATUS(status) == 0))
        failure = "the OpenVDB reader stopped before it finished";
    if (!failure.empty()) {
        if (WIFSIGNALED(status) && WTERMSIG(status) != SIGKILL)
            failure = "not a readable OpenVDB file (the reader crashed on it: signal " +
                      std::to_string(WTERMSIG(status)) + ")";
        throw Error(name, failure);
    }
    return grid;
}

}  // namespace sombra
