// A participating medium (spec §26): what fills a volume of space and
// absorbs, scatters and emits light along the rays through it. Version 4's
// first step: homogeneous media, filling the space outside every object.
#pragma once

#include <cstdint>
#include <string>

#include "core/vec3.h"

namespace sombra {

struct Medium {
    std::string name;     // its key in the scene file's "media"
    Vec3 sigma_a{0.0f};   // absorption per scene unit, the file's `scale` applied (≥ 0)
    Vec3 sigma_s{0.0f};   // scattering per scene unit, the file's `scale` applied (≥ 0)
    float g = 0.0f;       // the Henyey–Greenstein mean cosine, in (−1, 1)
    Vec3 emission{0.0f};  // radiance added per unit length travelled (not × σ_a, not scaled)
};

// "No medium": vacuum.
inline constexpr std::uint32_t kNoMedium = 0xffffffffu;

// σ_t = σ_a + σ_s: how much is taken from a ray per unit length.
inline Vec3 extinction(const Medium& m) { return m.sigma_a + m.sigma_s; }

}  // namespace sombra
