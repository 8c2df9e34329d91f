// The viewer's render (spec §20): one thread runs the progressive passes of
// render_image (the same code as `sombra render`) and publishes the image
// after each pass; a change of camera or settings cancels the passes and
// starts them again. Readers (the server's request threads) take the latest
// frame or wait for a newer one; the render never waits for a reader.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

#include "accel/accel.h"
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
};

class LiveRender {
public:
    // Starts the render thread on `initial`. `scene` and `accel` must outlive it.
    LiveRender(const Scene& scene, const Accel& accel, const ViewSettings& initial, int threads,
               LightSelection light_selection);
    ~LiveRender();  // cancels the passes and joins the thread
    LiveRender(const LiveRender&) = delete;
    LiveRender& operator=(const LiveRender&) = delete;

    // Cancels the passes under way (within a pixel's samples) and starts anew on `settings`.
    void restart(const ViewSettings& settings);
    ViewSettings settings() const;
    // The job render_image runs for `settings` (explain traces its samples with it).
    RenderJob job_for(const ViewSettings& settings) const;

    ViewFrame latest() const;
    // The latest frame once its version is above `version`, or after
    // `timeout`, or once stop() was called: whichever comes first.
    ViewFrame wait_newer(std::uint64_t version, std::chrono::milliseconds timeout) const;
    // Ends the passes and wakes every waiter; later waits return at once.
    void stop();
    bool stopped() const;

private:
    void run();

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
    RenderProgress progress_;  // its cancel flag stops render_image
    std::thread thread_;
};

}  // namespace sombra
