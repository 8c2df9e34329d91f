// The shading context a light term is evaluated in: the interaction, the
// material resolved there, its BSDF frame and the outgoing direction. The
// integrators hand it to the sample recorder with each term.
#pragma once

#include "render/bsdf/bsdf.h"
#include "render/interaction.h"
#include "scene/material.h"

namespace sombra {

struct ShadingView {
    const SurfaceInteraction& si;
    const Material& material;
    const BsdfPoint& bsdf_point;
    Vec3 wo;
};

}  // namespace sombra
