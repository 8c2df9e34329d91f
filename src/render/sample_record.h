// The story of one sample, as the integrators computed it (`sombra explain`,
// spec §14): every term of the rendering equation that went into the value,
// written down by the very code that renders. The integrators take a
// recorder as a template parameter: NoRecorder, whose hooks are empty and
// vanish from the compiled render loop, or SampleRecorder
// (render/sample_recorder.h), which fills a SampleRecord.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "core/vec3.h"
#include "render/bsdf/bsdf.h"
#include "scene/material.h"
#include "scene/scene.h"

namespace sombra {

inline constexpr std::uint32_t kNoTriangle = 0xffffffffu;

// What a shadow ray met first, when something blocked it.
struct BlockerRecord {
    std::uint32_t triangle = kNoTriangle;  // index into surface_mesh(scene, instance)
    std::uint32_t instance = kNoInstance;  // index into Scene::instances, or kNoInstance
    float distance = 0;                    // from the shadow ray's origin
};

// The surface a ray hit.
struct HitRecord {
    std::uint32_t triangle = kNoTriangle;  // index into surface_mesh(scene, instance)
    std::uint32_t instance = kNoInstance;  // index into Scene::instances, or kNoInstance
    std::uint32_t material = 0;            // index into Scene::materials
    float t = 0;                           // ray parameter (the ray's direction is not unit length for camera rays)
    float distance = 0;                    // |x − ray origin|
    float b1 = 0, b2 = 0;                  // barycentric weights of the second and third corner
    Vec3 position, n_g, n_s;  // n_g faces the ray's origin, n_s in n_g's hemisphere (after normal or bump maps)
    Vec3 n_c;                 // a clearcoat's own normal (SurfaceInteraction::n_c); zero: the coat, if any, uses n_s
    bool outside = true;      // arrived on the winding normal's side
    Vec2 uv;                  // texture coordinates at the hit ((0, 0) without)
    bool has_uv = false;
    float uv_footprint =
        0;  // mip-mapping: the ray cone's width in uv that textures were filtered over; 0: full resolution
    // The material as the BSDFs saw it here: for a textured material, each
    // textured parameter is its value at uv (spec §12), not the constant.
    Material shaded;
};

enum class LightOutcome {
    Behind,       // n_g·ω_i ≤ 0: the light is behind the surface
    OnSurface,    // the light sits on the shaded point: it lights nothing
    OutsideCone,  // a spot light's cone does not reach the point (s = 0): no shadow ray
    Blocked,      // the shadow ray met something (see blocker)
    Visible,      // it contributes
};

// Where a ray crossed a triangle whose surface is cut out at that point
// (spec §12): the ray went on as if nothing were there.
struct HoleRecord {
    std::uint32_t triangle = 0;
    float t = 0;       // along the ray, as the hit's t
    float alpha = 0;   // the surface's alpha there, below...
    float cutoff = 0;  // ...its material's cutoff
};
// The most holes one ray's record lists (nearest first); more are counted.
inline constexpr std::size_t kMaxHolesListed = 8;

// One delta light's term at a vertex (point, spot or directional, spec §4,
// §16): L += β · incident · f_r · |n_s·ω_i|.
struct DeltaLightRecord {
    std::uint32_t light = 0;  // its identity in the light set (= its index in Scene::lights)
    LightOutcome outcome = LightOutcome::Visible;
    Vec3 wi;                        // unit, towards the light
    float distance = 0;             // |c − x|; +∞ for a directional light
    float cos_g = 0;                // n_g·ω_i
    float cos_s = 0;                // |n_s·ω_i|
    float spot_factor = 1;          // a spot's falloff s² at ω_i (1 for other kinds)
    Vec3 incident;                  // point: I/|c − x|²; spot: I·s²/|c − x|²; directional: E
    BsdfTerms f_terms;              // f_r split into its lobes (render/bsdf/bsdf.h's kLobeNames)
    Vec3 f;                         // f_r as the integrator evaluated it
    BlockerRecord blocker;          // when Blocked
    std::vector<HoleRecord> holes;  // when Visible: the cut-outs the shadow ray went through
    std::size_t holes_crossed = 0;  // how many in all (holes lists at most kMaxHolesListed)
    Vec3 transmittance{1.0f};       // of the media the shadow ray crossed (spec §26); 1 in vacuum
    Vec3 contribution;              // what was added to the sample's value (0 unless Visible)
};

// The one emitter or environment direction sampled for next-event
// estimation at a path vertex, MIS-weighted against BSDF sampling.
struct SampledLightRecord {
    bool sampled = false;                  // false: no light could be sampled (or none carries anything)
    bool environment = false;              // the environment rather than an emitting triangle
    std::uint32_t light = kNoTriangle;     // its identity in the light set (render/lights/lights.h)
    std::uint32_t triangle = kNoTriangle;  // of surface_mesh(scene, instance)
    std::uint32_t instance = kNoInstance;  // the instance the emitter lies in (kNoInstance: the world)
    Vec3 wi;                               // unit, towards the sampled point
    Vec3 target;                           // the sampled point on the emitter
    float distance = 0;                    // to the sampled point (infinite for the environment)
    Vec3 radiance;                         // L_e arriving along −ω_i
    float light_pdf = 0;                   // solid-angle density of next-event estimation (with the choice of light)
    float bsdf_pdf = 0;                    // the BSDF's density for the same direction
    float mis_weight = 0;                  // power heuristic (1 when only lights are sampled)
    float cos_s = 0;                       // |n_s·ω_i|
    float cos_light = 0;  // |n_light·ω_i| at the sampled point of an emitting triangle (0 for the environment)
    BsdfTerms f_terms;    // f_r split into its lobes (render/bsdf/bsdf.h's kLobeNames)
    Vec3 f;               // f_r whole
    LightOutcome outcome = LightOutcome::Visible;  // Behind (f_r = 0, no shadow ray), Blocked, or Visible
    BlockerRecord blocker;
    std::vector<HoleRecord> holes;  // when Visible: the cut-outs the shadow ray went through
    std::size_t holes_crossed = 0;  // how many in all
    Vec3 transmittance{1.0f};       // of the media the shadow ray crossed (spec §26); 1 in vacuum
    Vec3 contribution;              // β · f·|cos| · L_e · w / pdf (· transmittance)
};

// Light reached by following the path: emission of a hit surface, or the
// environment when the ray left the scene.
struct EmissionRecord {
    bool present = false;
    Vec3 radiance;         // L_e
    float mis_weight = 1;  // 1 for what the camera or a delta bounce sees
    float bsdf_pdf = 0;    // density of the bounce that found it (0: camera or delta)
    float light_pdf = 0;   // density with which next-event estimation would have found it
    Vec3 contribution;     // β · L_e · w
};

// The direction sampled from the BSDF at a path vertex, and what became of the path.
struct BounceRecord {
    bool sampled = false;  // false: sampling produced no direction; the path ends
    Vec3 wi;
    Vec3 f;         // f_r(ω_o, ω_i) for a non-delta lobe
    float pdf = 0;  // solid-angle density (delta: the lobe's selection probability)
    bool delta = false, transmission = false;
    Vec3 weight;            // f·|n_s·ω_i| / pdf
    Vec3 throughput;        // β after this bounce (before Russian roulette)
    bool roulette = false;  // Russian roulette was played after this bounce
    float roulette_q = 1;   // survival probability
    float roulette_u = 0;   // the random number it drew
    bool survived = true;
    Vec3 throughput_after;  // β after roulette (÷ q for survivors)
};

// A stretch of participating medium (spec §26) the ray travelled through on
// its way to a vertex.
struct MediumSegmentRecord {
    std::uint32_t medium = 0;  // index into Scene::media
    float distance = 0;        // travelled in it (+∞: an unbounded medium with no surface ahead)
    bool scattered = false;    // the path scattered where it ends: a medium vertex
    // What β was multiplied by: T/P(passing) through it, or T·σ_s/p(t) to
    // the scattering point (1 per channel for a grey medium's free flight).
    Vec3 weight{1.0f};
    Vec3 emission;  // the medium's own light reaching the ray's origin, β·∫T·ε, added to the value
};

// An "interface" surface the ray crossed unchanged (spec §26).
struct CrossingRecord {
    std::uint32_t triangle = kNoTriangle;
    std::uint32_t instance = kNoInstance;
    float distance = 0;              // from the ray's origin
    std::uint32_t medium_after = 0;  // the medium beyond it (kNoMedium: vacuum)
    std::size_t after_segments = 0;  // how many of the vertex's segments come before it
};

// One vertex of the path: a surface hit, a scattering event in a medium
// (medium_event), or the ray's escape (neither).
struct VertexRecord {
    int depth = 0;             // scattering events before this vertex
    Vec3 ray_origin, ray_dir;  // the ray that arrived here (direction unit length)
    bool hit = false;
    HitRecord surface;
    std::vector<HoleRecord> holes;  // cut-outs the arriving ray crossed before the hit (or escaping)
    std::size_t holes_crossed = 0;  // how many in all (holes lists at most kMaxHolesListed)
    Vec3 throughput;                // β arriving here
    EmissionRecord emission;        // surface emission, or the environment on a miss
    std::vector<DeltaLightRecord> delta_lights;
    SampledLightRecord sampled_light;
    bool delta_material = false;  // no next-event estimation at a delta BSDF
    BounceRecord bounce;
    // Spec §26: the media and interfaces the arriving ray crossed, in order.
    std::vector<MediumSegmentRecord> segments;
    std::vector<CrossingRecord> crossings;
    // A scattering event in a medium: the phase function plays the BSDF
    // (its value for the delta and sampled lights' f, cos 1), and the
    // bounce is its sample (pdf = value, weight 1).
    bool medium_event = false;
    std::uint32_t medium = 0;  // index into Scene::media
    Vec3 position;             // where it scattered
};

// One sample of one pixel, from camera ray to value.
struct SampleRecord {
    int pixel_x = 0, pixel_y = 0, sample = 0;
    float offset_x = 0.5f, offset_y = 0.5f;  // position inside the pixel
    float s = 0, t = 0;                      // image-plane coordinates (spec §3)
    bool lens = false;                       // a thin lens (spec §17): the ray left the lens point (lens_u, lens_v)
    float lens_u = 0.5f, lens_v = 0.5f;      // the lens sample in [0, 1)², mapped to the disc by concentric_disc
    Vec3 origin, direction;                  // the camera ray (direction as the camera gives it, not unit)
    bool path = false;                       // integrator: path (else direct)
    std::vector<VertexRecord> vertices;      // direct: at most one
    std::string end;                         // why the path ended, in words
    bool nonfinite = false;                  // the raw value was NaN or infinite and counts as 0
    Vec3 value;                              // the sample's value: exactly what the render adds to its pixel
};

}  // namespace sombra
