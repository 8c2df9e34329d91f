#include "render/lights/lights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "render/shading.h"
#include "scene/cutout.h"

namespace sombra {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// The box around a mesh's finite positions (empty: lo > hi).
void grow_bounds(const TriangleMesh& mesh, Vec3& lo, Vec3& hi) {
    for (const Vec3& p : mesh.positions)
        if (is_finite(p)) {
            lo = min(lo, p);
            hi = max(hi, p);
        }
}

// The radius of a sphere around the scene's bounding box: the world
// geometry's and each instance's mesh box carried to world space (a
// little looser than its flattened copy's box, and far cheaper).
float bounding_radius(const Scene& scene) {
    if (scene.geometry.positions.empty() && scene.instances.empty()) return 1.0f;
    Vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
    grow_bounds(scene.geometry, lo, hi);
    std::vector<std::array<Vec3, 2>> mesh_boxes;
    for (const TriangleMesh& mesh : scene.instanced_meshes) {
        Vec3 mlo{std::numeric_limits<float>::max()}, mhi{-std::numeric_limits<float>::max()};
        grow_bounds(mesh, mlo, mhi);
        mesh_boxes.push_back({mlo, mhi});
    }
    for (const Instance& instance : scene.instances) {
        const auto [mlo, mhi] = mesh_boxes[instance.mesh];
        if (!(mlo.x <= mhi.x)) continue;
        for (int k = 0; k < 8; ++k) {
            const Vec3 corner{(k & 1) ? mhi.x : mlo.x, (k & 2) ? mhi.y : mlo.y, (k & 4) ? mhi.z : mlo.z};
            const Vec3 p = transform_point(instance.object_to_world, corner);
            if (!is_finite(p)) continue;
            lo = min(lo, p);
            hi = max(hi, p);
        }
    }
    const float r = 0.5f * length(hi - lo);
    return r > 0.0f && std::isfinite(r) ? r : 1.0f;
}

// The probability of choosing a constant environment (a `background` under
// path tracing) when the scene has emitters too.
constexpr double kConstantEnvironmentShare = 0.01;

// The probability of choosing some emitter rather than the environment.
float emitters_choice_probability(const LightSet& lights) {
    if (lights.emitters.empty()) return 0.0f;
    return lights.choice_cdf[lights.emitters.size() - 1];
}

// False when y, a point sampled on emitter e, lies where its surface is cut
// out. In an instance y is carried back to the mesh's coordinates, where
// its barycentrics are the same (the transform is affine).
bool sampled_point_exists(const Scene& scene, Emitter e, Vec3 y) {
    const TriangleMesh& mesh = surface_mesh(scene, e.instance);
    if (e.instance != kNoInstance) y = transform_point(scene.instances[e.instance].world_to_object, y);
    float b1 = 0, b2 = 0;
    if (!point_barycentrics(mesh, e.triangle, y, b1, b2)) return true;
    return surface_exists(Cutouts{&mesh, &scene.materials, &scene.textures}, e.triangle, b1, b2);
}

// The probability that sample_light, at x with normal n, chooses emitter e.
float emitter_choice(const LightSet& lights, Vec3 x, Vec3 n, std::size_t e) {
    return lights.use_tree
               ? emitters_choice_probability(lights) * pmf_light_tree(lights.tree, x, n, static_cast<std::uint32_t>(e))
               : lights.choice_probability[e];
}

// Pairs the emitters that make rectangles: neighbours in the emitter order
// (a quad's two triangles, or a mesh's, are consecutive) of one instance
// and one material.
void find_emitter_rectangles(const Scene& scene, LightSet& lights) {
    lights.emitter_rectangle.assign(lights.emitters.size(), kNoRectangle);
    for (std::size_t i = 0; i + 1 < lights.emitters.size(); ++i) {
        const Emitter a = lights.emitters[i], b = lights.emitters[i + 1];
        if (a.instance != b.instance) continue;
        const TriangleMesh& mesh = surface_mesh(scene, a.instance);
        if (mesh.material_ids[a.triangle] != mesh.material_ids[b.triangle]) continue;
        EmitterRectangle rect;
        if (!find_rectangle(world_triangle_corners(scene, a.triangle, a.instance),
                            world_triangle_corners(scene, b.triangle, b.instance), rect))
            continue;
        rect.near = static_cast<std::uint32_t>(i);
        rect.far = static_cast<std::uint32_t>(i + 1);
        lights.emitter_rectangle[i] = lights.emitter_rectangle[i + 1] =
            static_cast<std::uint32_t>(lights.rectangles.size());
        lights.rectangles.push_back(rect);
        ++i;
    }
}

// The position of emitter `e` in lights.emitters, or lights.emitters.size().
std::size_t find_emitter(const LightSet& lights, Emitter e) {
    const auto it = std::lower_bound(lights.emitters.begin(), lights.emitters.end(), e,
                                     [](const Emitter& a, const Emitter& b) { return a.key() < b.key(); });
    if (it == lights.emitters.end() || it->key() != e.key()) return lights.emitters.size();
    return static_cast<std::size_t>(it - lights.emitters.begin());
}

}  // namespace

LightSet make_light_set(const Scene& scene, Environment environment, bool sample_environment_light,
                        LightSelection selection) {
    LightSet lights;
    lights.delta = scene.lights;
    std::vector<float> power;
    std::vector<LightTreeEmitter> tree_emitters;
    // Emitter e with material m, its world corners p0 p1 p2 (winding order).
    auto add = [&](Emitter e, const Material& m, Vec3 p0, Vec3 p1, Vec3 p2) {
        const float area = 0.5f * length(cross(p1 - p0, p2 - p0));
        // Degenerate or non-finite triangles are never hit, so never lights.
        if (!(area > 0.0f) || !std::isfinite(area)) return;
        lights.emitters.push_back(e);
        lights.emitter_areas.push_back(area);
        const float sides = m.emits_front_only ? 1.0f : 2.0f;
        power.push_back(std::max(luminance(m.ke), 1e-6f * max_component(m.ke)) * area * kPi * sides);
        tree_emitters.push_back({p0, p1, p2, power.back(), !m.emits_front_only});
    };
    const TriangleMesh& mesh = scene.geometry;
    for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
        const Material& m = scene.materials[mesh.material_ids[t]];
        if (!is_emissive(m)) continue;
        const auto [p0, p1, p2] = triangle_corners(mesh, t);
        add(Emitter{t, kNoInstance}, m, p0, p1, p2);
    }
    // Each instance's emitting triangles (found once per mesh), placed in
    // world space: the light tree bounds them there, nothing is copied.
    std::vector<std::vector<std::uint32_t>> mesh_emitters(scene.instanced_meshes.size());
    for (std::size_t k = 0; k < scene.instanced_meshes.size(); ++k) {
        const TriangleMesh& im = scene.instanced_meshes[k];
        for (std::uint32_t t = 0; t < im.triangle_count(); ++t)
            if (is_emissive(scene.materials[im.material_ids[t]])) mesh_emitters[k].push_back(t);
    }
    for (std::uint32_t i = 0; i < scene.instances.size(); ++i) {
        const TriangleMesh& im = scene.instanced_meshes[scene.instances[i].mesh];
        for (const std::uint32_t t : mesh_emitters[scene.instances[i].mesh]) {
            const auto [p0, p1, p2] = instanced_triangle_corners(scene, t, i);
            add(Emitter{t, i}, scene.materials[im.material_ids[t]], p0, p1, p2);
        }
    }
    lights.use_tree = selection == LightSelection::Tree ||
                      (selection == LightSelection::Automatic && tree_emitters.size() >= kLightTreeMinEmitters);
    if (lights.use_tree) {
        // Powers that underflow or overflow float would weigh nothing in the tree.
        for (LightTreeEmitter& e : tree_emitters)
            if (!(e.power > 0.0f) || !std::isfinite(e.power)) e.power = 1.0f;
        lights.tree = make_light_tree(tree_emitters);
    }
    find_emitter_rectangles(scene, lights);
    lights.environment = std::move(environment);
    lights.environment_lights = sample_environment_light && !is_black(lights.environment);
    if (lights.environment_lights) {
        float env_power = 0;
        if (has_map(lights.environment) || power.empty()) {
            const float r = bounding_radius(scene);
            env_power = std::max(environment_power_proxy(lights.environment), 1e-12f) * kPi * r * r;
        } else {
            // A constant environment is what BSDF sampling finds best (the
            // cosine lobe is its exact density on a diffuse surface), so light
            // samples spent on it by power are mostly wasted. It keeps a small
            // share so that both strategies still count it.
            double emitters = 0;
            for (const float p : power) emitters += p;
            env_power = static_cast<float>(emitters * kConstantEnvironmentShare / (1.0 - kConstantEnvironmentShare));
        }
        power.push_back(env_power);
    }

    double total = 0;
    for (float p : power) total += p;
    if (!(total > 0.0) || !std::isfinite(total)) {
        // Powers too small or too large to weigh: choose uniformly.
        std::fill(power.begin(), power.end(), 1.0f);
        total = static_cast<double>(power.size());
    }
    double running = 0;
    for (float p : power) {
        lights.choice_probability.push_back(static_cast<float>(p / total));
        running += p;
        lights.choice_cdf.push_back(static_cast<float>(running / total));
    }
    if (!lights.choice_cdf.empty()) lights.choice_cdf.back() = 1.0f;
    return lights;
}

bool sample_light(const LightSet& lights, const Scene& scene, Vec3 x, Vec3 n, float u_choice, float u1, float u2,
                  LightSample& out) {
    if (!lights.has_sampled_lights()) return false;
    std::size_t chosen = 0;
    float choice = 0;
    const float emitter_share = emitters_choice_probability(lights);
    if (lights.use_tree && u_choice < emitter_share) {
        // The emitters' share of u_choice, stretched back onto [0, 1), picks in the tree.
        const float u = std::min(u_choice / emitter_share, 0x1.fffffep-1f);
        const LightTreeChoice tc = sample_light_tree(lights.tree, x, n, u);
        chosen = tc.emitter;
        choice = emitter_share * tc.probability;
    } else {
        const auto it = std::upper_bound(lights.choice_cdf.begin(), lights.choice_cdf.end(), u_choice);
        chosen = static_cast<std::size_t>(std::min<std::ptrdiff_t>(
            it - lights.choice_cdf.begin(), static_cast<std::ptrdiff_t>(lights.choice_cdf.size()) - 1));
        choice = lights.choice_probability[chosen];
    }
    if (!(choice > 0.0f)) return false;

    if (chosen == lights.emitters.size()) {
        EnvironmentSample es;
        if (!sample_environment(lights.environment, u1, u2, es) || !(es.pdf > 0.0f)) return false;
        out.radiance = es.radiance;
        out.wi = es.direction;
        out.at_infinity = true;
        out.pdf = choice * es.pdf;
        out.light = lights.environment_light();
        out.triangle = 0xffffffffu;
        return max_component(out.radiance) > 0.0f;
    }

    Vec3 y, wi, n_w;
    float pdf = 0;
    if (lights.emitter_rectangle[chosen] != kNoRectangle) {
        // The rectangle as one light: both triangles' chances of being chosen.
        const EmitterRectangle& rect = lights.rectangles[lights.emitter_rectangle[chosen]];
        choice += emitter_choice(lights, x, n, chosen == rect.near ? rect.far : rect.near);
        bool in_near = true;
        if (!sample_emitter_rectangle(rect, x, u1, u2, y, wi, pdf, in_near)) return false;
        n_w = rect.unit_normal;
        chosen = in_near ? rect.near : rect.far;
    } else {
        const Emitter e = lights.emitters[chosen];
        const auto [p0, p1, p2] = world_triangle_corners(scene, e.triangle, e.instance);
        n_w = normalize(cross(p1 - p0, p2 - p0));
        if (!sample_emitter_triangle(x, p0, p1, p2, n_w, lights.emitter_areas[chosen], u1, u2, y, wi, pdf))
            return false;
    }
    const Emitter e = lights.emitters[chosen];
    const Material& m = scene.materials[surface_mesh(scene, e.instance).material_ids[e.triangle]];
    // One-sided emitters shine only toward their winding normal's side.
    if (m.emits_front_only && dot(n_w, wi) >= 0.0f) return false;
    // A point on a cut-out part of the emitter is no light (spec §12).
    if (m.textures.alpha_test && !sampled_point_exists(scene, e, y)) return false;
    if (!(pdf > 0.0f) || !std::isfinite(pdf)) return false;
    out.radiance = emission_at(scene, m, e.triangle, y, e.instance);
    out.wi = wi;
    out.target = y;
    out.at_infinity = false;
    out.pdf = choice * pdf;
    out.light = lights.first_emitter() + static_cast<std::uint32_t>(chosen);
    out.triangle = e.triangle;
    out.instance = e.instance;
    return true;
}

float pdf_light_triangle(const LightSet& lights, const Scene& scene, std::uint32_t triangle, std::uint32_t instance,
                         Vec3 x, Vec3 n, Vec3 y) {
    const std::size_t e = find_emitter(lights, Emitter{triangle, instance});
    if (e == lights.emitters.size()) return 0.0f;
    if (lights.emitter_rectangle[e] != kNoRectangle) {
        const EmitterRectangle& rect = lights.rectangles[lights.emitter_rectangle[e]];
        const float choice = emitter_choice(lights, x, n, rect.near) + emitter_choice(lights, x, n, rect.far);
        return choice > 0.0f ? choice * pdf_emitter_rectangle(rect, x, y) : 0.0f;
    }
    const float choice = emitter_choice(lights, x, n, e);
    if (!(choice > 0.0f)) return 0.0f;
    const auto [p0, p1, p2] = world_triangle_corners(scene, triangle, instance);
    const Vec3 n_w = normalize(cross(p1 - p0, p2 - p0));
    return choice * pdf_emitter_triangle(x, p0, p1, p2, n_w, lights.emitter_areas[e], y);
}

LightKind light_kind(const LightSet& lights, const Scene& scene, std::uint32_t light) {
    if (light < lights.first_emitter()) return LightKind::Delta;
    if (light >= lights.environment_light()) return LightKind::Environment;
    const Emitter e = lights.emitters[light - lights.first_emitter()];
    return scene.materials[surface_mesh(scene, e.instance).material_ids[e.triangle]].emits_front_only
               ? LightKind::Quad
               : LightKind::Triangle;
}

std::uint32_t emitter_light(const LightSet& lights, std::uint32_t triangle, std::uint32_t instance) {
    const std::size_t e = find_emitter(lights, Emitter{triangle, instance});
    if (e == lights.emitters.size()) return kNoLight;
    return lights.first_emitter() + static_cast<std::uint32_t>(e);
}

float pdf_light_environment(const LightSet& lights, Vec3 dir) {
    if (!lights.environment_lights) return 0.0f;
    return lights.choice_probability.back() * pdf_environment(lights.environment, dir);
}

}  // namespace sombra
