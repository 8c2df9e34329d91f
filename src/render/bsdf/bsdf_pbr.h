// Spec §11's `pbr` material (glTF 2.0 metallic–roughness) as render/bsdf/bsdf.cpp
// dispatches to it; render/bsdf/bsdf.h states the conventions and the model.
// Internal to render/.
#pragma once

#include "core/vec3.h"
#include "render/bsdf/bsdf.h"
#include "scene/material.h"

namespace sombra {

// eval_bsdf, pdf_bsdf, sample_bsdf and is_delta_bsdf for m.type == Pbr; the
// first two are 0 for wi on the other side of n_g unless transmits_diffusely(m).
// With KHR_materials_clearcoat (m.clearcoat > 0) they are the coated
// material of render/bsdf/bsdf_pbr_layers.cpp over the sheen layer's below.
Vec3 eval_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
float pdf_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
bool sample_pbr(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2, BsdfSample& out);
bool is_delta_pbr(const Material& m);
// eval_pbr's parts: the diffuse base (1 − m)(1 − F)·c/π, the specular lobe,
// the transmission, the coat and the sheen.
BsdfTerms eval_pbr_terms(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);

// The same for the material without its coat: with KHR_materials_sheen
// (some sheen_color channel > 0) the sheen layer over the base of
// render/bsdf/bsdf_pbr_sheen.cpp, else the base's below, bit for bit.
Vec3 eval_pbr_sheen(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
float pdf_pbr_sheen(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
bool sample_pbr_sheen(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2,
                      BsdfSample& out);
bool is_delta_pbr_sheen(const Material& m);
BsdfTerms eval_pbr_terms_sheen(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);

// The same for the material without coat and sheen (glTF's core model with
// KHR_materials_specular, transmission and volume; render/bsdf/bsdf_pbr.cpp).
Vec3 eval_pbr_base(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
float pdf_pbr_base(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
bool sample_pbr_base(const Material& m, const BsdfPoint& p, Vec3 wo, float u_lobe, float u1, float u2, BsdfSample& out);
bool is_delta_pbr_base(const Material& m);
BsdfTerms eval_pbr_terms_base(const Material& m, const BsdfPoint& p, Vec3 wo, Vec3 wi);
// transmission_eta_scale for m.type == Pbr.
float pbr_transmission_eta_scale(const Material& m, bool outside);

}  // namespace sombra
