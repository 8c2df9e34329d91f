// Spatial splits for the binary builder (Stich, Friedrich and Dietrich,
// "Spatial splits in bounding volume hierarchies", 2009): a node may be cut
// at an axis-aligned plane, a triangle that straddles it going to both
// children, each time with the box of its part on that side. Internal to
// src/accel; bvh_build.cpp decides when to try one.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/bvh_build_refs.h"
#include "scene/mesh.h"

namespace sombra::bvh_build {

// Spatial bins per axis, as many as the object split's.
inline constexpr int kSpatialBins = 32;

struct SpatialSplit {
    int axis = -1;      // -1: none found within the budget
    int plane = 0;      // the cut is at the lower face of bin `plane` (1 … bins − 1)
    float cost = kInf;  // as Split::cost: half_area · blocks_of(count), summed over both sides
    std::uint32_t left_count = 0, right_count = 0;  // references per side, straddling ones on both
    Box left_bounds, right_bounds;
};

// The box of the part of triangle (v[0], v[1], v[2]) inside `box` on each side
// of the plane x[axis] = plane, each conservative: it contains every point
// of the triangle in `box` on that side (points on the plane on both), to
// within the float rounding of the edge crossings, which is padded outwards.
// Either may come back empty (Box::empty()).
void clip_triangle_box(const Vec3 v[3], const Box& box, int axis, float plane, Box& left, Box& right);

// The cheapest spatial split of refs[range.begin, range.end): kSpatialBins
// equal bins per axis over range.bounds, each reference chopped into the
// bins it crosses by clip_triangle_box against its triangle's corners (read
// from `mesh`). Only planes that add at most range.spare() references are
// considered. Deterministic (depends on the references alone, not on order).
SpatialSplit find_spatial_split(const PrimRef* refs, const RefRange& range, const TriangleMesh& mesh);

// Sorts refs[range.begin, range.end) to the sides of `split` into `left` and
// `right` (cleared first), in their order; a straddling reference is clipped
// into both, or goes whole to one side where the SAH says that is cheaper
// (Stich's reference unsplitting) or its part on the other side is empty.
// left.size() ≤ split.left_count and right.size() ≤ split.right_count; either
// may come out empty, and then the split is unusable.
void partition_spatial(const PrimRef* refs, const RefRange& range, const SpatialSplit& split,
                       const TriangleMesh& mesh, std::vector<PrimRef>& left, std::vector<PrimRef>& right);

}  // namespace sombra::bvh_build
