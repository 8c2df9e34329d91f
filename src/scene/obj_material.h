// MTL materials of an OBJ (spec §5, §9): where tinyobjloader finds the MTL
// files, and how their parameters become sombra's diffuse and Phong materials.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "core/error.h"
#include "scene/material.h"

namespace sombra {

// Opens the files named by `mtllib` relative to the OBJ's folder and records
// which file each material came from. A missing file is a warning (in
// tinyobjloader's warning text); its materials are then unknown names.
class MtlBesideObj final : public tinyobj::MaterialReader {
public:
    explicit MtlBesideObj(std::filesystem::path obj_folder) : folder_(std::move(obj_folder)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* name_to_index, std::string* warn, std::string* err) override;

    // The MTL path material i came from, as a WHERE for messages; `fallback` if unknown.
    const std::string& source(std::size_t i, const std::string& fallback) const {
        return i < sources_.size() ? sources_[i] : fallback;
    }

private:
    std::filesystem::path folder_;
    std::vector<std::string> sources_;
};

// Kd → kd; Ks > 0 in any channel → Phong with ks and shininess Ns, else
// diffuse; Ke → ke. Colours are clamped to [0, 1] (Ke only to >= 0, it is a
// radiance) and Ns to [0, kMaxMtlShininess], each with a warning at `where`.
Material material_from_mtl(const tinyobj::material_t& mtl, const std::string& where, Diagnostics& diag);

inline constexpr float kMaxMtlShininess = 1e6f;

}  // namespace sombra
