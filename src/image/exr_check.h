// The walk of an OpenEXR file that exr_reader.cpp runs before OpenEXR reads it.
#pragma once

#include <filesystem>
#include <string>

namespace sombra {

// OpenEXR allocates what a file claims (an attribute's size, the buffers of
// a chunk as wide as the data window) before it reads the bytes, so a file
// of a few hundred bytes could ask for gigabytes. This checks, from the
// file's bytes alone, that it is a single-part flat EXR file (scanlines, or
// tiles at any levels) whose header attributes lie inside the file, whose
// data and display windows lie inside the image limits, whose line-offset
// table points at every pixel chunk (every tile of every level) inside the
// file with none overlapping, and whose chunks each claim no more bytes than
// are left in the file nor than their pixels hold uncompressed. Returns the
// rows to read at a time (a chunk's, or a row of tiles); throws
// Error(where, ...) otherwise.
int check_exr_file(const std::filesystem::path& path, const std::string& where);

}  // namespace sombra
