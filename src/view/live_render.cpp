#include "view/live_render.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "denoise/denoise.h"

namespace sombra {

LiveRender::LiveRender(const Scene& scene, const Accel& accel, const ViewSettings& initial, int threads,
                       LightSelection light_selection, bool denoise)
    : scene_(scene), accel_(accel), threads_(threads), light_selection_(light_selection), settings_(initial) {
    frame_.generation = 1;
    frame_.denoise = denoise;  // before the first pass: it gathers the layers from the start
    frame_.target_spp = initial.settings.spp;
    thread_ = std::thread([this] { run(); });
    denoiser_ = std::thread([this] { denoise_passes(); });
}

LiveRender::~LiveRender() {
    stop();
    thread_.join();
    denoiser_.join();
}

void LiveRender::restart(const ViewSettings& settings) {
    const std::lock_guard lock(mutex_);
    restart_locked(settings);
}

void LiveRender::restart_locked(const ViewSettings& settings) {
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
    // A denoised image of the old passes would show the old camera.
    layers_.reset();
    denoise_cancel_.store(true);
    frame_.denoised = 0;
    frame_.denoised_spp = 0;
    frame_.denoised_image.reset();
    changed_.notify_all();
}

void LiveRender::set_denoise(bool on) {
    const std::lock_guard lock(mutex_);
    if (frame_.denoise == on) return;
    frame_.denoise = on;
    ++frame_.updates;
    if (on) {
        // Passes that began without the denoiser's layers start again with them.
        if (!gathering_ && !pending_) restart_locked(settings_);
    } else {
        denoise_cancel_.store(true);
        taken_version_ = 0;  // turned on again, the newest pass is denoised anew
        frame_.denoised = 0;
        frame_.denoised_spp = 0;
        frame_.denoised_image.reset();
    }
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

ViewFrame LiveRender::wait_newer(std::uint64_t updates, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return stop_ || frame_.updates > updates; });
    return frame_;
}

void LiveRender::stop() {
    const std::lock_guard lock(mutex_);
    stop_ = true;
    progress_.cancel.store(true);
    denoise_cancel_.store(true);
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
        bool gather = false;
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return stop_ || pending_; });
            if (stop_) return;
            settings = settings_;
            pending_ = false;
            progress_.cancel.store(false);
            gather = gathering_ = frame_.denoise;
        }
        RenderJob job = job_for(settings);
        job.aovs.denoise = gather;
        const auto start = Clock::now();
        job.on_pass = [&](const Accumulation& acc, int passes) {
            // The copies are made outside the lock: readers wait only for the swap.
            auto image = std::make_shared<const Film>(acc.mean_image());
            const int spp = acc.pixels() > 0 ? static_cast<int>(acc.count(0)) : 0;
            // The denoiser compares each pixel's two halves: it needs 2 samples.
            std::shared_ptr<const DenoiseLayers> layers;
            if (gather && spp >= 2) layers = std::make_shared<const DenoiseLayers>(acc.aov_images().denoise);
            const std::lock_guard lock(mutex_);
            if (pending_ || stop_) return;  // a restart is coming: this image is stale
            frame_.image = std::move(image);
            frame_.passes = passes;
            frame_.spp = spp;
            frame_.seconds = std::chrono::duration<double>(Clock::now() - start).count();
            frame_.done = spp >= settings.settings.spp;
            ++frame_.version;
            ++frame_.updates;
            if (layers) {
                layers_ = std::move(layers);
                layers_version_ = frame_.version;
                layers_spp_ = spp;
            }
            changed_.notify_all();
        };
        render_image(job, progress_);
    }
}

void LiveRender::denoise_passes() {
    for (;;) {
        std::shared_ptr<const DenoiseLayers> layers;
        std::uint64_t version = 0, generation = 0;
        int spp = 0;
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock,
                          [&] { return stop_ || (frame_.denoise && layers_ && layers_version_ != taken_version_); });
            if (stop_) return;
            layers = layers_;
            version = taken_version_ = layers_version_;
            generation = frame_.generation;
            spp = layers_spp_;
            denoise_cancel_.store(false);
        }
        std::vector<float> rgb = denoise_image(*layers, threads_, &denoise_cancel_);
        if (rgb.empty()) continue;  // cancelled: by a restart, the switch or stop
        auto image = std::make_shared<Film>(layers->width, layers->height);
        image->rgb = std::move(rgb);
        const std::lock_guard lock(mutex_);
        if (stop_ || !frame_.denoise || frame_.generation != generation) continue;
        frame_.denoised = version;
        frame_.denoised_spp = spp;
        frame_.denoised_image = std::move(image);
        ++frame_.updates;
        changed_.notify_all();
    }
}

}  // namespace sombra
