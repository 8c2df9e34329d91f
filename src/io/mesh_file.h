// Mesh files → LoadedMesh: OBJ (+MTL), PLY and glTF 2.0.
#pragma once

#include <filesystem>

#include "core/error.h"
#include "scene/mesh.h"

namespace sombra {

// Reads an OBJ file and the MTL files it names (spec §5, §9). Polygons are
// fan-triangulated from their first corner (concave ones ear-clipped); faces
// with fewer than 3 corners, triangles touching non-finite positions and
// out-of-range normal indices are dropped or ignored with a warning.
// Throws Error("file:line", ...) for a file that cannot be read or is invalid.
LoadedMesh load_obj(const std::filesystem::path& path, Diagnostics& diag);

// Reads an ascii or binary (little/big endian) PLY file (spec §9).
LoadedMesh load_ply(const std::filesystem::path& path, Diagnostics& diag);

// Reads a glTF 2.0 file, .gltf (JSON, external or embedded buffers) or .glb
// (spec §13): the default scene's meshes in the file's world space (node
// transforms applied), its materials as `pbr`, its point lights and first
// perspective camera. Throws Error(path, ...) for a broken file.
LoadedMesh load_gltf(const std::filesystem::path& path, Diagnostics& diag);

// Dispatches on the extension (.obj, .ply, .gltf or .glb, case-insensitive); throws
// Error(path, ...) for any other, for a missing file, or a folder.
LoadedMesh load_mesh_file(const std::filesystem::path& path, Diagnostics& diag);

}  // namespace sombra
