// OpenVDB files (spec §26): one float grid read as a grid medium's density,
// with Debian's libopenvdb. The file is untrusted input: its size, its
// claims about the grid and the dense box it becomes are bounded before
// anything they size is allocated by sombra.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "scene/density_grid.h"

namespace sombra {

// The largest VDB file read, and the most voxels the grid's active box may
// hold once dense (4 bytes each: 512 MiB).
inline constexpr std::uintmax_t kMaxVdbFileBytes = std::uintmax_t{2} << 30;
inline constexpr std::uint64_t kMaxDenseVoxels = std::uint64_t{1} << 27;

// Grid `grid` of the OpenVDB file `path`: its active voxels (values finite
// and ≥ 0) in a dense box padded with zeros, its index-to-world transform
// (affine; a frustum is refused) and its majorants. Errors (a missing or
// unreadable file, no such grid, a grid of another type, too large, a bad
// value) are sombra::Error naming the file, in one line.
DensityGrid read_vdb_density(const std::filesystem::path& path, const std::string& grid);

}  // namespace sombra
