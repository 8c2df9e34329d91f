// A ray o + t·d for t in (0, tmax), both ends open. d need not be unit length: t is measured
// in multiples of d, which lets camera rays keep the assignment's unnormalised
// directions and shadow rays reach their light at t = 1.
#pragma once

#include <limits>

#include "core/vec3.h"

namespace sombra {

struct Ray {
    Vec3 origin;
    Vec3 dir;
    float tmax = std::numeric_limits<float>::infinity();
};

// False for rays that could only produce NaN or visit every box: a non-finite
// origin or direction, or a zero direction. Every backend lets them hit nothing.
inline bool is_traceable(const Ray& ray) { return is_finite(ray.origin) && is_finite(ray.dir) && ray.dir != Vec3{}; }

}  // namespace sombra
