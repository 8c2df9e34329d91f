// Choosing a mesh loader by the file's extension.
#include "scene/mesh_file.h"

#include <algorithm>
#include <cctype>

namespace sombra {

LoadedMesh load_mesh_file(const std::filesystem::path& path, Diagnostics& diag) {
    namespace fs = std::filesystem;
    const std::string where = path.string();
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (status.type() == fs::file_type::not_found) throw Error(where, "no such file");
    if (status.type() == fs::file_type::directory) throw Error(where, "is a folder, not a mesh file");

    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension == ".obj") return load_obj(path, diag);
    if (extension == ".ply") return load_ply(path, diag);
    throw Error(where, extension.empty() ? "mesh file has no extension (expected .obj or .ply)"
                                         : "unsupported mesh file type '" + extension + "' (expected .obj or .ply)");
}

}  // namespace sombra
