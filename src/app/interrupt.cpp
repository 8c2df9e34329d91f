#include "app/interrupt.h"

#include <poll.h>
#include <pthread.h>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <utility>

namespace sombra {

const char* signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "signal"; }

InterruptWatcher::InterruptWatcher(RenderProgress& progress) : progress_(progress) {
    sigemptyset(&blocked_);
    sigaddset(&blocked_, SIGINT);
    sigaddset(&blocked_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &blocked_, &previous_mask_);
    // The watcher sleeps in poll() on the blocked signals (a signalfd) and on
    // an eventfd the destructor writes to, so that a run ends the moment its
    // work is done instead of waiting up to a whole tick of a timed wait at
    // exit. Without the descriptors (none left), it falls back to that timed
    // wait.
    signal_fd_ = signalfd(-1, &blocked_, SFD_CLOEXEC);
    wake_fd_ = eventfd(0, EFD_CLOEXEC);
    thread_ = std::thread([this] { watch(); });
}

InterruptWatcher::~InterruptWatcher() {
    stop_.store(true);
    if (wake_fd_ >= 0) {
        const std::uint64_t one = 1;
        [[maybe_unused]] const ssize_t written = write(wake_fd_, &one, sizeof one);
    }
    thread_.join();
    if (signal_fd_ >= 0) close(signal_fd_);
    if (wake_fd_ >= 0) close(wake_fd_);
    // A signal that arrives from here on gets its default action again.
    pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

void InterruptWatcher::on_interrupt(std::function<void()> stop) {
    const std::lock_guard lock(on_interrupt_mutex_);
    on_interrupt_ = std::move(stop);
}

int InterruptWatcher::next_signal() {
    if (signal_fd_ < 0 || wake_fd_ < 0) {
        // Waking ten times a second to check stop_ keeps the reaction to a
        // signal well under a second.
        const timespec tick{0, 100'000'000};
        return sigtimedwait(&blocked_, nullptr, &tick);
    }
    pollfd fds[2] = {{signal_fd_, POLLIN, 0}, {wake_fd_, POLLIN, 0}};
    if (poll(fds, 2, -1) <= 0 || (fds[1].revents & POLLIN) != 0) return 0;  // EINTR, or woken to stop
    signalfd_siginfo info{};
    if (read(signal_fd_, &info, sizeof info) != static_cast<ssize_t>(sizeof info)) return 0;
    return static_cast<int>(info.ssi_signo);
}

void InterruptWatcher::watch() {
    while (!stop_.load()) {
        const int sig = next_signal();
        if (sig <= 0) continue;
        signal_.store(sig);
        progress_.cancel.store(true);
        if (phase_.load() == Phase::Serving) {
            const std::lock_guard lock(on_interrupt_mutex_);
            if (on_interrupt_) on_interrupt_();
            continue;
        }
        if (phase_.load() == Phase::Failed) std::_Exit(interrupted_exit_status(sig));  // one line was enough
        if (phase_.load() == Phase::Preparing) {
            // Loading a large mesh cannot be cut short, and nothing has been
            // written yet: leave now. _Exit runs no destructors that could
            // wait on the busy main thread.
            if (isatty(STDERR_FILENO)) std::fputs("\r\033[K", stderr);  // over the progress bar, if any
            std::fprintf(stderr, "sombra: error: %s: interrupted, nothing written\n", signal_name(sig));
            std::fflush(stderr);
            std::_Exit(interrupted_exit_status(sig));
        }
    }
}

}  // namespace sombra
