// Reading a polygon mesh file (OBJ, PLY: the "Polygon File Format") whole,
// with the file-level errors both loaders report the same way.
#pragma once

#include <filesystem>
#include <string>

namespace sombra {

// The file's bytes. Throws Error(path, "no such file"), Error(path, "is a
// folder, not a mesh file"), or Error(path, ...) when it cannot be read.
std::string read_polygon_file(const std::filesystem::path& path);

}  // namespace sombra
