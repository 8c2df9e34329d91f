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

}  // namespace sombra
