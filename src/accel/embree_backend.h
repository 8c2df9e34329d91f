// The Embree yardstick (`--accel embree`): Intel's Embree 3 answers the same
// two questions as sombra's BVH, so the BVH's speed can be measured against a
// production kernel on the same scenes with the same shading code. Compiled
// only when CMake finds Embree 3 (then SOMBRA_HAVE_EMBREE is defined).
//
// Embree is used as it comes: default scene flags (RTC_SCENE_FLAG_NONE, so
// not the watertight "robust" mode, which the benchmarks may ask for) and the
// default build quality (RTC_BUILD_QUALITY_MEDIUM; RTC_BUILD_QUALITY_HIGH,
// its spatial-split builder, on request), one triangle geometry over the
// whole mesh. A scene's instances (spec §23) use Embree's own instancing:
// one Embree scene per instanced mesh, drawn by RTC_GEOMETRY_TYPE_INSTANCE
// geometries in a top-level scene beside the world mesh.
// Hits agree with the BVH's to float rounding, not bit for bit: Embree's
// Möller–Trumbore variant rounds differently, is not watertight at edges, and
// does not send ties at equal t to the lower triangle index.
#pragma once

#ifdef SOMBRA_HAVE_EMBREE

#include <cstddef>
#include <memory>

#include "core/ray.h"
#include "scene/cutout.h"
#include "scene/mesh.h"

namespace sombra {

struct Hit;
struct Scene;

// An Embree device and committed scene over one mesh, plus the buffers shared
// with Embree; opaque outside embree_backend.cpp.
struct EmbreeScene;

// Builds Embree's BVH over the triangles of `mesh` that sombra can hit (the
// same ones make_bvh keeps: in-range indices, finite corners, non-zero area).
// The mesh must outlive the result. Throws Error("embree", ...) when Embree
// fails (unsupported CPU, out of memory). With active `cutouts` (over
// `mesh`, outliving the result), Embree's filter functions drop the hits
// where the surface is cut out. `high_quality` builds with
// RTC_BUILD_QUALITY_HIGH instead of the default MEDIUM; `robust` sets
// RTC_SCENE_FLAG_ROBUST (conservative box tests, rays do not slip between
// triangles: a fairer yardstick for traversal, and slower; but a ray spawned
// off a surface by its error bound then hits that surface at t = 0, so it is
// no renderer's backend).
std::shared_ptr<const EmbreeScene> make_embree_scene(const TriangleMesh& mesh, const Cutouts& cutouts = {},
                                                     bool high_quality = false, bool robust = false);

// The same for a whole scene: its world geometry (with `world_cutouts`) and
// its instances, each instanced mesh built once as its own Embree scene
// (with its own cut-outs) and drawn by one instance geometry per
// Scene::instances entry. The scene must outlive the result.
std::shared_ptr<const EmbreeScene> make_embree_scene(const Scene& scene, const Cutouts& world_cutouts,
                                                     bool high_quality = false, bool robust = false);

// Closest hit with 0 < t < ray.tmax; (b1, b2) are Embree's (u, v), which are
// the weights of the triangle's second and third corner as in sombra, and
// hit.triangle is the index into mesh.triangles; through an instance,
// hit.instance is its index in Scene::instances (Embree's instID), and
// (b1, b2) and hit.triangle are the instanced mesh's own. Returns false and leaves
// `hit` untouched on a miss. The ray must be traceable (finite origin,
// finite non-zero direction): accel.cpp checks that before calling.
bool intersect_embree(const EmbreeScene& scene, const Ray& ray, Hit& hit);

// True when any triangle is hit with 0 < t < ray.tmax.
bool occluded_embree(const EmbreeScene& scene, const Ray& ray);

// Bytes held for the structure beyond the mesh itself: what Embree allocated
// (summed by a device memory monitor, net of frees, after the commit) plus
// sombra's copies handed to Embree (the padded vertex buffer and, when some
// triangles were left out, the filtered index buffer and its index map).
std::size_t embree_memory_bytes(const EmbreeScene& scene);

}  // namespace sombra

#endif  // SOMBRA_HAVE_EMBREE
