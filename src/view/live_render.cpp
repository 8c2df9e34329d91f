#include "view/live_render.h"

#include <algorithm>
#include <utility>

namespace sombra {

LiveRender::LiveRender(const Scene& scene, const Accel& accel, const ViewSettings& initial, int threads,
                       LightSelection light_selection)
    : scene_(scene), accel_(accel), threads_(threads), light_selection_(light_selection), settings_(initial) {
    frame_.generation = 1;
    frame_.target_spp = initial.settings.spp;
    thread_ = std::thread([this] { run(); });
}

LiveRender::~LiveRender() {
    stop();
    thread_.join();
}

void LiveRender::restart(const ViewSettings& settings) {
    const std::lock_guard lock(mutex_);
    settings_ = settings;
    pending_ = true;
    progress_.cancel.store(true);
    // From now on the frame describes the new passes; the old image stays
    // on show until the first of them ends.
    ++frame_.generation;
    frame_.passes = 0;
    frame_.spp = 0;
    frame_.target_spp = settings.settings.spp;
    frame_.seconds = 0;
    frame_.done = false;
    changed_.notify_all();
}

ViewSettings LiveRender::settings() const {
    const std::lock_guard lock(mutex_);
    return settings_;
}

RenderJob LiveRender::job_for(const ViewSettings& settings) const {
    RenderJob job = make_render_job(scene_, accel_, settings.settings, threads_, light_selection_);
    job.camera = make_camera(settings.camera, settings.settings.width, settings.settings.height);
    job.limits.pass_samples = kViewPassSamples;
    return job;
}

ViewFrame LiveRender::latest() const {
    const std::lock_guard lock(mutex_);
    return frame_;
}

ViewFrame LiveRender::wait_newer(std::uint64_t version, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return stop_ || frame_.version > version; });
    return frame_;
}

void LiveRender::stop() {
    const std::lock_guard lock(mutex_);
    stop_ = true;
    progress_.cancel.store(true);
    changed_.notify_all();
}

bool LiveRender::stopped() const {
    const std::lock_guard lock(mutex_);
    return stop_;
}

void LiveRender::run() {
    using Clock = std::chrono::steady_clock;
    for (;;) {
        ViewSettings settings;
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return stop_ || pending_; });
            if (stop_) return;
            settings = settings_;
            pending_ = false;
            progress_.cancel.store(false);
        }
        RenderJob job = job_for(settings);
        const auto start = Clock::now();
        job.on_pass = [&](const Accumulation& acc, int passes) {
            // The copy is made outside the lock: readers wait only for the swap.
            auto image = std::make_shared<const Film>(acc.mean_image());
            const int spp = acc.pixels() > 0 ? static_cast<int>(acc.count(0)) : 0;
            const std::lock_guard lock(mutex_);
            if (pending_ || stop_) return;  // a restart is coming: this image is stale
            frame_.image = std::move(image);
            frame_.passes = passes;
            frame_.spp = spp;
            frame_.seconds = std::chrono::duration<double>(Clock::now() - start).count();
            frame_.done = spp >= settings.settings.spp;
            ++frame_.version;
            changed_.notify_all();
        };
        render_image(job, progress_);
    }
}

}  // namespace sombra
