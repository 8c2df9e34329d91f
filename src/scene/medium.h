// A participating medium (spec §26): what fills a volume of space and
// absorbs, scatters and emits light along the rays through it: the same
// everywhere (homogeneous), or scaled by the density of an OpenVDB grid.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/vec3.h"
#include "scene/density_grid.h"
#include "scene/transform.h"

namespace sombra {

struct Medium {
    std::string name;     // its key in the scene file's "media"
    Vec3 sigma_a{0.0f};   // absorption per scene unit, the file's `scale` applied (≥ 0)
    Vec3 sigma_s{0.0f};   // scattering per scene unit, the file's `scale` applied (≥ 0)
    float g = 0.0f;       // the Henyey–Greenstein mean cosine, in (−1, 1)
    Vec3 emission{0.0f};  // radiance added per unit length travelled (not × σ_a, not scaled)
    // A grid medium: its coefficients are sigma_a·d(x) and sigma_s·d(x), d
    // the density (no emission). Null: homogeneous. Shared by the copies of
    // the medium that the objects bounding it place (scene loading).
    std::shared_ptr<const DensityGrid> density;
    // World space → the density's dense coordinates (its index-to-world
    // transform, then the object's, inverted, then the dense box's origin).
    Transform world_to_grid;
};

// "No medium": vacuum.
inline constexpr std::uint32_t kNoMedium = 0xffffffffu;

// σ_t = σ_a + σ_s: how much is taken from a ray per unit length.
inline Vec3 extinction(const Medium& m) { return m.sigma_a + m.sigma_s; }

}  // namespace sombra
