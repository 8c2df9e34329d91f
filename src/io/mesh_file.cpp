// Mesh files: reading one whole (read_mesh_file, for both loaders) and
// choosing the loader by the file's extension.
#include "io/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include <sys/stat.h>

#include "core/error.h"
#include "io/mesh_builder.h"

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
    if (extension == ".gltf" || extension == ".glb") return load_gltf(path, diag);
    throw Error(where, extension.empty()
                           ? "mesh file has no extension (expected .obj, .ply, .gltf or .glb)"
                           : "unsupported mesh file type '" + extension + "' (expected .obj, .ply, .gltf or .glb)");
}

std::string instance_name(const InstancedPart& part, std::size_t k) {
    const auto after = std::upper_bound(part.origins.begin(), part.origins.end(), k,
                                        [](std::size_t i, const InstancedPart::Origin& o) { return i < o.first; });
    if (after == part.origins.begin()) return "instance " + std::to_string(k);
    const InstancedPart::Origin& o = *(after - 1);
    return o.numbered ? o.name + ": instance " + std::to_string(k - o.first) : o.name;
}

namespace {

// strerror's text with a lower-case first letter, as our messages are.
std::string reason(int err) {
    std::string text = std::strerror(err);
    if (!text.empty()) text[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
    return text;
}

}  // namespace

OpenMeshFile open_mesh_file(const std::filesystem::path& path) {
    namespace fs = std::filesystem;
    const std::string where = path.string();
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (status.type() == fs::file_type::not_found) throw Error(where, "no such file");
    if (ec) throw Error(where, "cannot read: " + ec.message());
    if (status.type() == fs::file_type::directory) throw Error(where, "is a folder, not a mesh file");
    // A FIFO or device could block forever or never end.
    if (status.type() != fs::file_type::regular) throw Error(where, "is not a regular file");

    OpenMeshFile opened{{std::fopen(path.c_str(), "rb"), &std::fclose}, 0};
    if (!opened.file) throw Error(where, "cannot open: " + reason(errno));
    struct stat info {};
    if (fstat(fileno(opened.file.get()), &info) == 0 && info.st_size > 0)
        opened.size_on_disk = static_cast<std::uint64_t>(info.st_size);
    return opened;
}

void read_rest_of_file(std::FILE* file, const std::string& where, std::string& bytes) {
    char chunk[1 << 16];
    std::size_t got = 0;
    // Read to the end rather than trusting the size on disk, which may change underneath.
    while ((got = std::fread(chunk, 1, sizeof chunk, file)) > 0) bytes.append(chunk, got);
    if (std::ferror(file)) throw Error(where, "cannot read: " + reason(errno));
}

std::string read_mesh_file(const std::filesystem::path& path) {
    const OpenMeshFile opened = open_mesh_file(path);
    std::string bytes;
    bytes.reserve(static_cast<std::size_t>(opened.size_on_disk));
    read_rest_of_file(opened.file.get(), path.string(), bytes);
    return bytes;
}

}  // namespace sombra
