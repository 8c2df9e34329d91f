// Next-event estimation for the delta lights (spec §4, §16): point, spot and
// directional lights, each visited at every vertex with one shadow ray.
// Shared by both integrators so that `path` at max_depth 1 gives `direct`'s
// pixels.
#pragma once

#include "accel/accel.h"
#include "render/bsdf.h"
#include "render/interaction.h"
#include "render/lights.h"
#include "render/ray_counters.h"

namespace sombra {

// Adds to `radiance`, for every delta light of `lights` on the viewer's side
// of n_g and not blocked, beta · f(ω_o, ω_i) · |n_s·ω_i| times what arrives:
// I/|c−x|² from a point light, I·s²/|c−x|² from a spot (s its falloff at
// ω_i, scene/light.h; nothing outside its cone, without a shadow ray), E
// from a directional light (shadow ray unbounded). One shadow ray per light
// that can contribute. The arithmetic is ordered as that formula reads, and
// for a point light with beta = 1 it is exactly version 1's. `recorder`
// (render/sample_recorder.h) hears every light's outcome; instantiated for
// NoRecorder and SampleRecorder.
template <class Recorder>
void add_delta_lights(const LightSet& lights, const Accel& accel, const SurfaceInteraction& si,
                      const Material& material, const BsdfPoint& bsdf_point, Vec3 wo, Vec3 beta, Vec3& radiance,
                      RayCounters& counters, Recorder& recorder);

}  // namespace sombra
