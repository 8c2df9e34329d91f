// Next-event estimation at a point inside a medium (spec §26): the light
// that arrives there, attenuated on its way, times the phase function, as
// add_delta_lights and sample_one_light do at a surface. Every delta light
// with one shadow ray each, and one sampled emitter or environment point
// weighted by MIS against the phase function's density for the same
// direction (the phase function is the BSDF of a medium vertex).
#pragma once

#include <cstdint>

#include "render/integrator.h"
#include "render/media/grid_medium.h"
#include "render/ray_counters.h"

namespace sombra {

// Radiance scattered at x towards −d_in (d_in: the unit direction the path
// travelled in) from the delta lights and one sampled light, through
// the scene's media, starting in `medium` (an index into Scene::media), and
// across interface surfaces (render/shadow_ray.h). Out of line:
// inlined, it made the path integrator's loop 3 % slower on scenes without media.
// Grid media's transmittance draws from `rng`; `recorder` (NoRecorder,
// FirstHitRecorder or SampleRecorder, instantiated in the .cpp) hears each
// light's term.
template <class Recorder>
Vec3 medium_direct_light(const IntegratorContext& ctx, std::uint32_t medium, Vec3 x, Vec3 d_in, float u_choice,
                         float u1, float u2, RayCounters& counters, TrackingRng& rng, Recorder& recorder);

}  // namespace sombra
