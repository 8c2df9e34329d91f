// Ctrl-C (SIGINT) and kill (SIGTERM) during a run: the render stops within a
// moment and nothing is written, so an existing image stays as it was.
//
// No signal handler and no global: the signals are blocked in every thread
// and one watcher thread takes them from a signalfd, then acts in plain code.
#pragma once

#include <atomic>
#include <csignal>
#include <functional>
#include <mutex>
#include <thread>

#include "render/render.h"

namespace sombra {

class InterruptWatcher {
public:
    enum class Phase {
        Preparing,  // loading and building: nothing to save, so the watcher exits the process at once
        Rendering,  // the watcher cancels the render; the run then stops without writing
        Writing,    // too late to stop: the (atomic) write completes and the run ends normally
        Serving,    // `sombra view`: the watcher calls the function given to on_interrupt, which ends the server
        Failed,     // the run's error is said: a signal (mpirun ending the ranks) ends the process quietly
    };

    // Must be constructed before any other thread exists (oneTBB's workers
    // included): the blocked signal mask is inherited by threads created later.
    explicit InterruptWatcher(RenderProgress& progress);
    ~InterruptWatcher();
    InterruptWatcher(const InterruptWatcher&) = delete;
    InterruptWatcher& operator=(const InterruptWatcher&) = delete;

    void set_phase(Phase phase) { phase_.store(phase); }
    // What the watcher calls (on its thread) when a signal arrives while
    // Serving; set it before entering that phase.
    void on_interrupt(std::function<void()> stop);
    // The signal received, or 0 when none was.
    int signal_received() const { return signal_.load(); }

private:
    void watch();
    // Waits for SIGINT or SIGTERM; 0 when woken without one (to stop, or spuriously).
    int next_signal();

    RenderProgress& progress_;
    std::atomic<Phase> phase_{Phase::Preparing};
    std::mutex on_interrupt_mutex_;
    std::function<void()> on_interrupt_;
    std::atomic<int> signal_{0};
    std::atomic<bool> stop_{false};
    sigset_t blocked_{};
    int signal_fd_ = -1;  // reads the blocked signals
    int wake_fd_ = -1;    // an eventfd the destructor writes to wake the watcher
    sigset_t previous_mask_{};
    std::thread thread_;
};

// "SIGINT", "SIGTERM": how messages name the signals the watcher takes.
const char* signal_name(int signal);

// The exit status for a run stopped by `signal`: 128 + the signal number, as shells report it.
inline int interrupted_exit_status(int signal) { return 128 + signal; }

}  // namespace sombra
