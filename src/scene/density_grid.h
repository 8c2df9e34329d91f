// The density of a grid medium (spec §26): an OpenVDB float grid's active
// voxels copied into a dense box, read by trilinear interpolation, and a
// coarse grid of the largest density in each block of voxels (the majorant
// that delta tracking samples against, render/media/grid_medium.h), so
// that thin smoke is not stepped through at the densest voxel's rate.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "scene/transform.h"

namespace sombra {

// Voxels a side of one majorant cell.
inline constexpr int kMajorantBlock = 8;

struct DensityGrid {
    std::string source;  // "smoke.vdb: density", for messages
    // The dense box: dims voxels, voxel (0, 0, 0) at the file's index
    // coordinates `origin`. It pads the active voxels' bounding box with one
    // voxel of 0 on every side, so that the interpolation falls to 0 at its
    // edge; inactive voxels inside hold 0 (spec §26: 0 outside the grid's
    // active voxels). x varies fastest, then y, then z.
    std::array<int, 3> dims{0, 0, 0};
    std::array<int, 3> origin{0, 0, 0};
    std::vector<float> values;  // finite, ≥ 0
    // Dense coordinates → the file's world space: the box's origin, then the
    // file's index-to-world transform (affine; voxel centres at integers).
    Transform index_to_world;

    // The majorant grid: for cell (a, b, c), the largest value interpolation
    // can give within dense coordinates [a, a + 1]·kMajorantBlock × … .
    std::array<int, 3> cells{0, 0, 0};
    std::vector<float> majorants;
    float max_value = 0;
};

// Fills `majorants`, `cells` and `max_value` from `values` and `dims`.
void build_majorants(DensityGrid& grid);

// The density at dense coordinates q (voxel (i, j, k) centred at (i, j, k)),
// trilinear; 0 outside the box.
inline float density_at(const DensityGrid& grid, Vec3 q) {
    const float fx = std::floor(q.x), fy = std::floor(q.y), fz = std::floor(q.z);
    if (!(fx >= 0.0f && fy >= 0.0f && fz >= 0.0f && fx < static_cast<float>(grid.dims[0] - 1) &&
          fy < static_cast<float>(grid.dims[1] - 1) && fz < static_cast<float>(grid.dims[2] - 1)))
        return 0.0f;
    const auto i = static_cast<std::size_t>(fx), j = static_cast<std::size_t>(fy), k = static_cast<std::size_t>(fz);
    const float tx = q.x - fx, ty = q.y - fy, tz = q.z - fz;
    const auto nx = static_cast<std::size_t>(grid.dims[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(grid.dims[1]);
    const float* v = grid.values.data() + i + j * nx + k * nxy;
    const auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
    const float c00 = lerp(v[0], v[1], tx), c10 = lerp(v[nx], v[nx + 1], tx);
    const float c01 = lerp(v[nxy], v[nxy + 1], tx), c11 = lerp(v[nxy + nx], v[nxy + nx + 1], tx);
    return lerp(lerp(c00, c10, ty), lerp(c01, c11, ty), tz);
}

}  // namespace sombra
