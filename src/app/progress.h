// The progress bar: while a render runs, a watcher thread redraws one
// terminal line with the share done, the samples done, the ray rate and
// the time left.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>

#include "render/render.h"

namespace sombra {

class ProgressBar {
public:
    // Starts drawing on stderr when `enabled` (a terminal and not --quiet);
    // otherwise does nothing at all. Under a time budget the bar also fills
    // with the time passed toward `deadline`, whichever is further.
    ProgressBar(const RenderProgress& progress, std::uint64_t total_samples, bool enabled,
                std::optional<std::chrono::steady_clock::time_point> deadline = std::nullopt);
    // Stops the watcher and clears the line.
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

private:
    void run();
    void draw(double elapsed_seconds) const;

    const RenderProgress& progress_;
    std::uint64_t total_samples_;  // width · height · spp
    std::chrono::steady_clock::time_point start_;
    std::optional<std::chrono::steady_clock::time_point> deadline_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace sombra
