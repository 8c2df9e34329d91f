// What a render counts while it traces (spec §6, §15's statistics).
#pragma once

#include <cstdint>

namespace sombra {

// Rays traced by one worker; summed over workers for the statistics.
struct RayCounters {
    std::uint64_t camera_rays = 0;
    std::uint64_t shadow_rays = 0;        // every next-event (shadow) ray
    std::uint64_t bounce_rays = 0;        // rays traced by BSDF sampling (path integrator)
    std::uint64_t nonfinite_samples = 0;  // samples whose radiance was NaN/Inf, dropped (counted as 0)

    std::uint64_t rays() const { return camera_rays + shadow_rays + bounce_rays; }
    RayCounters& operator+=(const RayCounters& b) {
        camera_rays += b.camera_rays;
        shadow_rays += b.shadow_rays;
        bounce_rays += b.bounce_rays;
        nonfinite_samples += b.nonfinite_samples;
        return *this;
    }
};

}  // namespace sombra
