// The lights of spec §4 and §10 as the integrators see them: they answer
// "from x, where are you and how much arrives" and never trace rays
// themselves (the integrator casts the shadow ray up to the returned
// distance). Point lights are delta lights, each visited at every vertex;
// emissive triangles and the environment are sampled one at a time: an
// environment map in proportion to its share of the power (a constant one
// rarely: see make_light_set), and among the
// emitters in proportion to power or, in scenes of many emitters, by a light
// tree that weighs each by what it can send to the shading point
// (render/lights/light_tree.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "render/interaction.h"
#include "render/lights/emitter_sampling.h"
#include "render/lights/environment.h"
#include "render/lights/light_tree.h"
#include "scene/scene.h"

namespace sombra {

// How sample_light chooses among the emissive triangles.
enum class LightSelection {
    Automatic,  // the tree from kLightTreeMinEmitters emitters on, power below
    Power,      // in proportion to power, wherever the shading point is
    Tree,       // by the light tree
};

// From this many emitters on, Automatic uses the light tree. Below it the
// tree's descent costs more than it saves (and with one or two emitters,
// the typical quad light, it would change nothing of note).
constexpr std::size_t kLightTreeMinEmitters = 8;

// What kind of light an entry of the light set is (spec §4, §10, §16).
enum class LightKind : std::uint8_t {
    Delta,        // a point, spot or directional light: LightSet::delta[light], its type there
    Quad,         // an emitting triangle of a quad light (one-sided)
    Triangle,     // an emitting triangle of a material with ke (two-sided)
    Environment,  // the background or environment map, when it lights (path)
};

inline constexpr std::uint32_t kNoLight = 0xffffffffu;

// An emitting triangle: `triangle` of surface_mesh(scene, instance), so an
// emissive mesh instanced N times is N lights (spec §23) whose triangles
// are stored once. Ordered world triangles first (kNoInstance), then by
// instance and triangle.
struct Emitter {
    std::uint32_t triangle = 0;
    std::uint32_t instance = kNoInstance;

    // kNoInstance + 1 wraps to 0: the world geometry sorts first.
    std::uint64_t key() const { return std::uint64_t{instance + 1u} << 32 | triangle; }
};

// Every light of one render, each once. A light's identity is its index in
// the set, the same for the integrators, `explain` and tests:
//   [0, delta.size())                         the delta lights (point, spot,
//                                             directional: scene.lights, in order);
//   [first_emitter(), environment_light())    the emitting triangles, in Emitter order (the
//                                             world's in triangle order, then each instance's);
//   environment_light()                       the environment, when environment_lights.
// The kinds live in per-kind arrays (plain data for the hot path): delta
// lights are visited one by one at every vertex (render/delta_lights.h);
// emitters and the environment are sampled one at a time below.
struct LightSet {
    std::vector<PunctualLight> delta;
    // Emissive triangles (material ke > 0), in increasing Emitter::key
    // order (so that a hit triangle is found by binary search), with their
    // world areas.
    std::vector<Emitter> emitters;
    std::vector<float> emitter_areas;
    Environment environment;
    bool environment_lights = false;  // the environment is sampled (path integrator, not black)
    // Probabilities of choosing each emitter, then (last, when
    // environment_lights) the environment, in proportion to power; their
    // running sums for sampling.
    std::vector<float> choice_probability;
    std::vector<float> choice_cdf;
    // The tree over `emitters` (same indices), when use_tree: the emitters
    // are then chosen by it, each with the probability the tree gives times
    // the emitters' share of the power (1 − the environment's).
    LightTree tree;
    bool use_tree = false;
    // The rectangles among the emitters, and for each emitter the index of
    // its rectangle or kNoRectangle.
    std::vector<EmitterRectangle> rectangles;
    std::vector<std::uint32_t> emitter_rectangle;

    bool has_sampled_lights() const { return !choice_probability.empty(); }

    std::uint32_t first_emitter() const { return static_cast<std::uint32_t>(delta.size()); }
    std::uint32_t environment_light() const { return first_emitter() + static_cast<std::uint32_t>(emitters.size()); }
    std::uint32_t light_count() const { return environment_light() + (environment_lights ? 1u : 0u); }
};

// The kind of light `light` (< lights.light_count()).
LightKind light_kind(const LightSet& lights, const Scene& scene, std::uint32_t light);

// The identity of emitting triangle `triangle` of surface_mesh(scene,
// instance), or kNoLight when it emits nothing.
std::uint32_t emitter_light(const LightSet& lights, std::uint32_t triangle, std::uint32_t instance = kNoInstance);

// The lights of `scene` for one render: its delta lights, its emitting
// triangles (the world's and every instance's) and the environment.
// `environment` lights the scene when `sample_environment_light` (under path
// tracing) and is otherwise only seen.
// Emitter power = luminance(ke) · area · π (twice for two-sided emitters);
// the environment's = its power proxy · π R², R the scene's bounding radius,
// except that a constant environment beside emitters is chosen with
// probability 0.01 (BSDF sampling serves it better).
LightSet make_light_set(const Scene& scene, Environment environment, bool sample_environment_light,
                        LightSelection selection = LightSelection::Automatic);

// What arrives at a point from one sampled light.
struct LightSample {
    Vec3 radiance;                   // L arriving along -wi (before the cosine and the BSDF)
    Vec3 wi;                         // unit direction from the point towards the light
    Vec3 target;                     // the sampled point on an emitter (for the shadow ray); unused for the environment
    bool at_infinity = false;        // environment: the shadow ray has no end
    float pdf = 0;                   // solid-angle density, including the probability of choosing this light
    std::uint32_t light = kNoLight;  // its identity in the light set
    std::uint32_t triangle = 0xffffffffu;  // the emitter triangle sampled (all ones for the environment)
    std::uint32_t instance = kNoInstance;  // the instance it lies in (kNoInstance: the world geometry)
};

// Samples one emitter or the environment for the point x with unit shading
// normal n (zero when unknown; the light tree then leaves out its cosine
// bound, which only sharpens the choice): u_choice picks the light, (u1, u2) a point on it: on a triangle uniform over the solid
// angle it subtends from x (render/lights/spherical_triangle.h) when that is
// between 0.05 and 6 sr, else uniform by area; likewise on a rectangle
// (EmitterRectangle, render/lights/spherical_rectangle.h).
// Returns false when nothing can be sampled or the sample carries nothing
// (the emitter is seen edge-on or from its dark side).
bool sample_light(const LightSet& lights, const Scene& scene, Vec3 x, Vec3 n, float u_choice, float u1, float u2,
                  LightSample& out);

// The solid-angle density with which sample_light, called at x with normal
// n (the same x and n), picks point y on emitter triangle `triangle` of
// surface_mesh(scene, instance) (0 when it is not a light, or the light
// tree gives it no chance from x).
float pdf_light_triangle(const LightSet& lights, const Scene& scene, std::uint32_t triangle, std::uint32_t instance,
                         Vec3 x, Vec3 n, Vec3 y);

// The solid-angle density with which sample_light picks direction `dir` on
// the environment (0 when the environment is not sampled).
float pdf_light_environment(const LightSet& lights, Vec3 dir);

// Radiance the surface at `si` emits back along the ray that hit it:
// ke, two-sided (spec §9), or only toward the winding normal's side for
// one-sided (quad light) emitters.
inline Vec3 emitted_radiance(const Material& material, const SurfaceInteraction& si) {
    if (material.emits_front_only && !si.outside) return Vec3{0.0f};
    return material.ke;
}

// The multiple-importance weight of a strategy with density `pdf_a` against
// one with `pdf_b` (Veach's power heuristic, β = 2).
inline float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    if (!(a > 0.0f)) return 0.0f;
    if (!std::isfinite(a)) return 1.0f;
    return a / (a + b);
}

}  // namespace sombra
