// Splitting one planar-ish polygon into triangles (spec §9): a fan from the
// first corner, unless the fan would overlap itself, in which case ear
// clipping on the polygon's best-fit plane. Shared by the OBJ and PLY loaders.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/vec3.h"

namespace sombra {

// Corner numbers (0 … n-1 within one polygon) of one output triangle.
using PolygonTriangle = std::array<std::uint32_t, 3>;

// How a polygon was split.
enum class PolygonSplit {
    Fan,         // (0,1,2), (0,2,3), …: triangles, quads, convex or star-shaped polygons
    EarClipped,  // the fan would overlap: ear clipping in the Newell plane
    OverlapFan,  // the fan overlaps but the polygon is too large to clip: fan kept
};

// Scratch memory reused across polygons, so that splitting allocates only
// while the largest polygon seen so far grows.
struct PolygonScratch {
    std::vector<double> u, v;  // corners projected onto the best-fit plane
    std::vector<std::uint32_t> prev, next;
};

// Polygons with more corners than this are never ear-clipped (clipping is
// quadratic or worse in the corner count): a fan is kept and reported.
inline constexpr std::size_t kMaxEarClipCorners = 256;

// Appends exactly corners.size() - 2 triangles to `out` (nothing when fewer
// than 3 corners), each wound like the polygon. Non-finite corners give a fan.
PolygonSplit triangulate_polygon(std::span<const Vec3> corners, PolygonScratch& scratch,
                                 std::vector<PolygonTriangle>& out);

}  // namespace sombra
