// The viewer's render (spec §20): one thread runs the progressive passes of
// render_image (the same code as `sombra render`) and publishes the image
// after each pass; a change of camera or settings cancels the passes and
// starts them again. Under the denoise switch (spec §25) a second thread
// denoises the newest finished pass whenever it is free, so the passes
// never wait for it. Readers (the server's request threads) take the latest
// frame or wait for a newer one; the render never waits for a reader.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

#include "accel/accel.h"
#include "denoise/denoise_layers.h"
#include "render/film.h"
#include "render/lights/lights.h"
#include "render/render.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace sombra {

// Samples each of the viewer's passes adds to every pixel: the finest step
// spec §18 allows, so that the first image comes soon.
inline constexpr int kViewPassSamples = 2;

// What restarts the passes when it changes.
struct ViewSettings {
    CameraSpec camera;        // the scene's, until the page sends a look-at camera
    RenderSettings settings;  // size, spp (where the passes stop), seed, integrator, max_depth
};

// The latest published image and how the render got there.
struct ViewFrame {
    std::uint64_t version = 0;          // 0 before the first pass; increases with every published pass
    std::uint64_t generation = 0;       // increases with every restart
    int passes = 0;                     // passes done since the restart
    int spp = 0;                        // samples every pixel has now
    int target_spp = 0;                 // where the passes stop
    double seconds = 0;                 // since the restart
    bool done = false;                  // spp reached: no pass follows until the next restart
    std::shared_ptr<const Film> image;  // null before the first pass

    bool denoise = false;                        // the denoise switch
    std::uint64_t denoised = 0;                  // the version of the pass denoised_image is; 0: none
    int denoised_spp = 0;                        // that pass's samples a pixel
    std::shared_ptr<const Film> denoised_image;  // of this generation, while the switch is on; else null
    std::uint64_t updates = 0;                   // increases with every pass, denoised image and switch

    // What the page shows: the newest denoised pass under the switch, else the newest pass.
    const std::shared_ptr<const Film>& shown() const { return denoised_image ? denoised_image : image; }
};

class LiveRender {
public:
    // Starts the render thread on `initial`, with the denoise switch as
    // `denoise` says. `scene` and `accel` must outlive it.
    LiveRender(const Scene& scene, const Accel& accel, const ViewSettings& initial, int threads,
               LightSelection light_selection, bool denoise = false);
    ~LiveRender();  // cancels the passes and joins the thread
    LiveRender(const LiveRender&) = delete;
    LiveRender& operator=(const LiveRender&) = delete;

    // Cancels the passes under way (within a pixel's samples) and starts anew on `settings`.
    void restart(const ViewSettings& settings);
    ViewSettings settings() const;
    // The job render_image runs for `settings` (explain traces its samples with it).
    RenderJob job_for(const ViewSettings& settings) const;

    // Turns the denoise switch on or off. While it is on, the passes gather
    // the denoiser's layers (turning it on restarts passes that do not) and,
    // from 2 samples a pixel on, the newest finished pass is denoised each
    // time the previous denoise is done: one at a time, none queued.
    // Turning it off, or a restart, drops the denoised image and cancels the
    // denoise under way.
    void set_denoise(bool on);

    ViewFrame latest() const;
    // The latest frame once its `updates` is above `updates`, or after
    // `timeout`, or once stop() was called: whichever comes first.
    ViewFrame wait_newer(std::uint64_t updates, std::chrono::milliseconds timeout) const;
    // Ends the passes and wakes every waiter; later waits return at once.
    void stop();
    bool stopped() const;

private:
    void run();
    void denoise_passes();
    void restart_locked(const ViewSettings& settings);

    const Scene& scene_;
    const Accel& accel_;
    int threads_;
    LightSelection light_selection_;

    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;  // a new frame, a restart or stop
    ViewSettings settings_;
    ViewFrame frame_;
    bool pending_ = true;  // settings_ changed since the passes began
    bool stop_ = false;
    RenderProgress progress_;                      // its cancel flag stops render_image
    bool gathering_ = false;                       // the passes under way gather the denoiser's layers
    std::shared_ptr<const DenoiseLayers> layers_;  // the newest pass's, while gathering (2 spp and more)
    std::uint64_t layers_version_ = 0;             // its frame version
    int layers_spp_ = 0;                           // and samples a pixel
    std::uint64_t taken_version_ = 0;              // the version the denoiser took last
    std::atomic<bool> denoise_cancel_{false};      // stops the denoise under way
    std::thread thread_;
    std::thread denoiser_;
};

}  // namespace sombra
