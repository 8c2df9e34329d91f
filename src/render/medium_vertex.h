// Next-event estimation at a point inside a medium (spec §26): the light
// that arrives there, attenuated on its way, times the phase function, as
// add_delta_lights and sample_one_light do at a surface. Every delta light
// with one shadow ray each, and one sampled emitter or environment point
// weighted by MIS against the phase function's density for the same
// direction (the phase function is the BSDF of a medium vertex).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "accel/accel.h"
#include "render/integrator.h"
#include "render/lights/delta_light_types.h"
#include "render/lights/lights.h"
#include "render/media/homogeneous_medium.h"
#include "render/media/phase_function.h"
#include "render/ray_counters.h"

namespace sombra {

// The length of a shadow ray's path through the medium: to the light, or
// unbounded for a light at infinity.
inline float shadow_length(bool at_infinity, Vec3 from, Vec3 to) {
    return at_infinity ? std::numeric_limits<float>::infinity() : length(to - from);
}

// Radiance scattered at x towards −d_in (d_in: the unit direction the path
// travelled in) from the delta lights and one sampled light, through
// `medium` (homogeneous, filling the space up to the lights). Out of line:
// inlined, it made the path integrator's loop 3 % slower on scenes without media.
Vec3 medium_direct_light(const IntegratorContext& ctx, const Medium& medium, Vec3 x, Vec3 d_in, float u_choice,
                         float u1, float u2, RayCounters& counters);

}  // namespace sombra
