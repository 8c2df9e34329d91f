#include "io/scene_input.h"

#include <cctype>

#include "io/quicklook.h"
#include "io/scene_json/scene_file.h"

namespace sombra {

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

LoadedScene load_input(const std::filesystem::path& input, Diagnostics& diag) {
    std::error_code ec;
    if (std::filesystem::is_directory(input, ec))
        throw Error(input.string(),
                    "is a folder, not a scene: give a scene .json or a model file (.obj, .ply, .gltf, "
                    ".glb), e.g. one inside it");
    const std::string ext = lower_extension(input);
    if (ext == ".json") return load_scene_file(input, diag);
    if (ext == ".obj" || ext == ".ply" || ext == ".gltf" || ext == ".glb") return make_quicklook_scene(input, diag);
    throw Error(input.string(),
                "unknown input type '" + ext + "' (expected a scene .json, or a model .obj, .ply, .gltf or .glb)");
}

}  // namespace sombra
