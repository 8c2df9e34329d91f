// Alpha cut-outs (spec §12, §13): where a material's alpha is below its
// cutoff the surface does not exist. It neither blocks, reflects nor emits,
// for camera, bounce and shadow rays alike, and a light sample landing there
// contributes nothing. The acceleration structures ask surface_exists() of
// every candidate hit on a cut-out material (accel/accel.h), so the
// integrators never see such a hit; light sampling asks it of sampled points.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/texture.h"

namespace sombra {

// The scene's surfaces as the alpha test reads them: borrowed, never owned
// (they must outlive whoever holds this). Inactive (mesh == nullptr) when no
// material has a cut-out: then every surface exists and traversal skips the
// test altogether.
struct Cutouts {
    const TriangleMesh* mesh = nullptr;
    const std::vector<Material>* materials = nullptr;  // indexed by mesh->material_ids
    const std::vector<Texture>* textures = nullptr;    // the materials' TextureRefs index this table
    bool active() const { return mesh != nullptr; }
};

// The cut-outs of a scene's world geometry; inactive when no material in
// `materials` has alpha_test set.
Cutouts make_cutouts(const TriangleMesh& mesh, const std::vector<Material>& materials,
                     const std::vector<Texture>& textures);

// The alpha of `m` at barycentric weights (b1, b2) of `triangle`: alpha_factor,
// times the alpha texture (at the point's uv, (0, 0) without uvs) when set,
// times the vertex colours' alpha (glTF COLOR_0) where the triangle has them.
float surface_alpha(const Cutouts& cutouts, const Material& m, std::uint32_t triangle, float b1, float b2);

// True when `alpha`, a surface's alpha of material `m` (alpha_test set) at
// some point, removes the surface there.
inline bool cut_out_at(const Material& m, float alpha) { return alpha < m.textures.alpha_cutoff; }

// False where the surface of `triangle` is cut out at (b1, b2).
inline bool surface_exists(const Cutouts& cutouts, std::uint32_t triangle, float b1, float b2) {
    const std::uint32_t id = cutouts.mesh->material_ids[triangle];
    if (id >= cutouts.materials->size()) return true;
    const Material& m = (*cutouts.materials)[id];
    return !m.textures.alpha_test || !cut_out_at(m, surface_alpha(cutouts, m, triangle, b1, b2));
}

}  // namespace sombra
