// Private to the OBJ loader: the textures an MTL material names (spec §12).
#pragma once

#include <tiny_obj_loader.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/material.h"

namespace sombra {

// Reads the maps of MTL materials into one OBJ's texture table, each file
// once per encoding, and points the materials at them:
//  - map_Kd, map_Ks, map_Ke: colour textures that replace Kd, Ks (kr for
//    illum 5), Ke (scale 1: a textured MTL colour is the texture, as Blender's
//    importer reads it; MTL files often leave Kd at a placeholder or out);
//    For a pbr material (Pr/Pm) map_Kd textures base_color, and map_Pr,
//    map_Pm (grey data) replace roughness and metallic;
//  - map_d: the cut-out alpha (its A channel, else its first), cutoff 0.5;
//  - bump / map_Bump: a height map, its -bm multiplier the bump scale;
//  - norm: a tangent-space normal map.
// `-clamp on` makes a map clamp instead of repeat. Texture paths are relative
// to the MTL file's folder; backslashes (Windows exporters) read as '/'. A
// missing or unreadable image is a warning, once per file, and the
// material keeps its constant.
class MtlTextureReader {
public:
    MtlTextureReader(std::vector<Texture>& table, Diagnostics& diag) : table_(table), diag_(diag) {}

    // Adds the maps of `mtl`, read from the MTL file `mtl_path`, to `m`.
    void apply(const tinyobj::material_t& mtl, const std::filesystem::path& mtl_path, Material& m);

private:
    TextureRef load(const std::string& name, const tinyobj::texture_option_t& options, TextureEncoding encoding,
                    const std::filesystem::path& folder, const std::filesystem::path& mtl_path);

    std::vector<Texture>& table_;
    Diagnostics& diag_;
    std::set<std::string> failed_;  // files already warned about
};

}  // namespace sombra
