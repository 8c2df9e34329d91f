#include "app/interrupt.h"

#include <pthread.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>

namespace sombra {

const char* signal_name(int signal) { return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "signal"; }

InterruptWatcher::InterruptWatcher(RenderProgress& progress) : progress_(progress) {
    sigemptyset(&blocked_);
    sigaddset(&blocked_, SIGINT);
    sigaddset(&blocked_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &blocked_, &previous_mask_);
    thread_ = std::thread([this] { watch(); });
}

InterruptWatcher::~InterruptWatcher() {
    stop_.store(true);
    thread_.join();
    // A signal that arrives from here on gets its default action again.
    pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
}

void InterruptWatcher::watch() {
    // Waking ten times a second to check stop_ costs nothing and keeps the
    // reaction to a signal well under a second.
    const timespec tick{0, 100'000'000};
    while (!stop_.load()) {
        const int sig = sigtimedwait(&blocked_, nullptr, &tick);
        if (sig <= 0) continue;
        signal_.store(sig);
        progress_.cancel.store(true);
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
