#include "scene/cutout.h"

namespace sombra {

Cutouts make_cutouts(const TriangleMesh& mesh, const std::vector<Material>& materials,
                     const std::vector<Texture>& textures) {
    for (const Material& m : materials)
        if (m.textures.alpha_test) return Cutouts{&mesh, &materials, &textures};
    return {};
}

float surface_alpha(const Cutouts& cutouts, const Material& m, std::uint32_t triangle, float b1, float b2) {
    const MaterialTextures& t = m.textures;
    float alpha = t.alpha_factor;
    if (t.alpha.is_set()) {
        Vec2 uv{0.0f, 0.0f};
        // Set 0 missing reads at (0, 0); a further set missing leaves the
        // factor alone, as shading does (render/shading.cpp).
        if (interpolate_uv_set(*cutouts.mesh, t.alpha.uv_set, triangle, b1, b2, uv) || t.alpha.uv_set == 0)
            alpha *= eval_texture_ref(*cutouts.textures, t.alpha, uv)[t.alpha.channel & 3u];
    }
    // glTF COLOR_0's alpha multiplies the material's (spec §13).
    Rgba color;
    if (interpolate_color(*cutouts.mesh, triangle, b1, b2, color)) alpha *= color[3];
    return alpha;
}

}  // namespace sombra
