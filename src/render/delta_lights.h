// Next-event estimation for point lights (spec §4), shared by both
// integrators so that `path` at max_depth 1 gives `direct`'s pixels.
#pragma once

#include "accel/accel.h"
#include "render/bsdf.h"
#include "render/integrator.h"
#include "render/interaction.h"

namespace sombra {

// Adds beta · I/|c−x|² · f(ω_o, ω_i) · |n_s·ω_i| to `radiance` for every
// point light that lies on the viewer's side of n_g and is not blocked,
// tracing one shadow ray per such light. The arithmetic is ordered as that
// formula reads, and with beta = 1 it is exactly version 1's. `recorder`
// (render/sample_recorder.h) hears every light's outcome; instantiated for
// NoRecorder and SampleRecorder.
template <class Recorder>
void add_point_lights(const Scene& scene, const Accel& accel, const SurfaceInteraction& si, const Material& material,
                      const BsdfPoint& bsdf_point, Vec3 wo, Vec3 beta, Vec3& radiance, RayCounters& counters,
                      Recorder& recorder);

}  // namespace sombra
