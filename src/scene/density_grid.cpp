#include "scene/density_grid.h"

#include <algorithm>

namespace sombra {

void build_majorants(DensityGrid& grid) {
    // Cells cover dense coordinates [0, dims − 1] in blocks; a point in a
    // block interpolates voxels from its first to one past its last.
    for (int a = 0; a < 3; ++a) grid.cells[a] = std::max(1, (grid.dims[a] - 1 + kMajorantBlock - 1) / kMajorantBlock);
    const auto cx = static_cast<std::size_t>(grid.cells[0]), cy = static_cast<std::size_t>(grid.cells[1]);
    grid.majorants.assign(cx * cy * static_cast<std::size_t>(grid.cells[2]), 0.0f);
    grid.max_value = 0.0f;
    const auto nx = static_cast<std::size_t>(grid.dims[0]), ny = static_cast<std::size_t>(grid.dims[1]);
    for (int k = 0; k < grid.dims[2]; ++k)
        for (int j = 0; j < grid.dims[1]; ++j)
            for (int i = 0; i < grid.dims[0]; ++i) {
                const float v = grid.values[static_cast<std::size_t>(i) + static_cast<std::size_t>(j) * nx +
                                            static_cast<std::size_t>(k) * nx * ny];
                if (!(v > 0.0f)) continue;
                grid.max_value = std::max(grid.max_value, v);
                // A voxel on a block's boundary feeds the blocks on both sides.
                const auto range = [](int voxel, int count) {
                    const int hi = std::min(voxel / kMajorantBlock, count - 1);
                    const int lo = voxel % kMajorantBlock == 0 && voxel > 0 ? hi - 1 : hi;
                    return std::array<int, 2>{std::max(lo, 0), hi};
                };
                const auto [x0, x1] = range(i, grid.cells[0]);
                const auto [y0, y1] = range(j, grid.cells[1]);
                const auto [z0, z1] = range(k, grid.cells[2]);
                for (int c = z0; c <= z1; ++c)
                    for (int b = y0; b <= y1; ++b)
                        for (int a = x0; a <= x1; ++a) {
                            float& m = grid.majorants[static_cast<std::size_t>(a) + static_cast<std::size_t>(b) * cx +
                                                      static_cast<std::size_t>(c) * cx * cy];
                            m = std::max(m, v);
                        }
            }
}

}  // namespace sombra
