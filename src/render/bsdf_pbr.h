// Spec §11's `pbr` material (glTF 2.0 metallic–roughness) as render/bsdf.cpp
// dispatches to it; render/bsdf.h states the conventions and the model.
// Internal to render/.
#pragma once

#include "core/vec3.h"
#include "render/bsdf.h"
#include "scene/material.h"

namespace sombra {

// eval_bsdf, pdf_bsdf, sample_bsdf and is_delta_bsdf for m.type == Pbr; the
// first two are 0 for wi on the other side of n_g unless transmits_diffusely(m).
Vec3 eval_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
float pdf_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
bool sample_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2, BsdfSample& out);
bool is_delta_pbr(const Material& m);
// transmission_eta_scale for m.type == Pbr.
float pbr_transmission_eta_scale(const Material& m, bool outside);
// eval_pbr's two parts: the diffuse base (1 − m)(1 − F)·c/π and the specular lobe.
BsdfTerms eval_pbr_terms(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);

}  // namespace sombra
