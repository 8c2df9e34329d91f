#include "app/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sombra {

ProgressBar::ProgressBar(const RenderProgress& progress, std::uint64_t total_samples, bool enabled,
                         std::optional<std::chrono::steady_clock::time_point> deadline)
    : progress_(progress),
      total_samples_(total_samples),
      start_(std::chrono::steady_clock::now()),
      deadline_(deadline) {
    if (enabled && total_samples_ > 0) thread_ = std::thread([this] { run(); });
}

ProgressBar::~ProgressBar() {
    if (!thread_.joinable()) return;
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
    std::fputs("\r\033[K", stderr);  // leave the line clean for the summary
    std::fflush(stderr);
}

void ProgressBar::run() {
    std::unique_lock lock(mutex_);
    // Redraw five times a second: smooth enough, and costs nothing.
    while (!wake_.wait_for(lock, std::chrono::milliseconds(200), [this] { return stop_; })) {
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start_;
        draw(elapsed.count());
    }
}

void ProgressBar::draw(double elapsed) const {
    constexpr int kWidth = 30;
    const auto samples = progress_.samples_done.load(std::memory_order_relaxed);
    double done = static_cast<double>(samples) / static_cast<double>(total_samples_);
    if (deadline_) {
        const std::chrono::duration<double> budget = *deadline_ - start_;
        if (budget.count() > 0) done = std::max(done, std::min(1.0, elapsed / budget.count()));
    }
    const double mrays =
        elapsed > 0 ? static_cast<double>(progress_.rays_traced.load(std::memory_order_relaxed)) / elapsed * 1e-6 : 0;
    char bar[kWidth + 1];
    const int filled = static_cast<int>(done * kWidth);
    for (int k = 0; k < kWidth; ++k) bar[k] = k < filled ? '#' : '-';
    bar[kWidth] = '\0';
    char eta[32] = "--";
    if (done > 0.01) {
        const long left = std::lround(elapsed * (1.0 - done) / done);
        std::snprintf(eta, sizeof eta, "%ld:%02ld", left / 60, left % 60);
    }
    char count[64];
    if (deadline_)  // the samples the budget allows are not known ahead
        std::snprintf(count, sizeof count, "%.1f M samples", static_cast<double>(samples) * 1e-6);
    else if (total_samples_ >= 10'000'000)
        std::snprintf(count, sizeof count, "%.1f/%.1f M samples", static_cast<double>(samples) * 1e-6,
                      static_cast<double>(total_samples_) * 1e-6);
    else
        std::snprintf(count, sizeof count, "%llu/%llu samples", static_cast<unsigned long long>(samples),
                      static_cast<unsigned long long>(total_samples_));
    std::fprintf(stderr, "\r\033[Ksombra: [%s] %3d%%  %s  %.1f Mrays/s  ETA %s", bar, static_cast<int>(done * 100),
                 count, mrays, eta);
    std::fflush(stderr);
}

}  // namespace sombra
