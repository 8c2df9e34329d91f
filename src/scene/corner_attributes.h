// The per-corner vertex attributes of a mesh joining the scene's world
// geometry (scene_builder.cpp): normals, texture coordinates, tangents and
// colours, each placed by the object's transform as what it is, their
// indices offset and wound like the triangles.
#pragma once

#include "scene/mesh.h"
#include "scene/transform.h"

namespace sombra {

// Appends `in`'s normals, uvs, tangents and colours to `out`, whose
// triangles already end with in's (placed by `transform`, corners 1 and 2
// swapped when it mirrors). Normals go by the inverse transpose, tangent
// directions by the linear part, both renormalised (those that vanish or
// overflow are dropped: their corners get none); a mirror flips each
// tangent's handedness, so that bitangent = handedness·(n × t) still follows
// the placed surface; uvs (every set) and colours are copied. Where only one side has an
// attribute the other's triangles get none (kNoNormal …).
void append_corner_attributes(TriangleMesh& out, const TriangleMesh& in, const Transform& transform);

// The same for a mesh already in world space: every value copied as it is,
// not renormalised (nor dropped).
void append_corner_attributes(TriangleMesh& out, const TriangleMesh& in);

// Derives mesh.complete_normals and complete_uvs from normal_indices and
// uv_indices: a bit a triangle, set when all three corners have the
// attribute; each left empty when the mesh has none of it.
void mark_complete_corners(TriangleMesh& mesh);

}  // namespace sombra
