#include "render/lights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "render/shading.h"
#include "render/spherical_triangle.h"
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

// Triangles subtending a solid angle in this range (estimated first, see
// spherical_triangle_to_sample) are sampled uniformly over it (spherical
// triangles); outside it by area. Below the range d² and
// cos θ vary little over the triangle, so area sampling is nearly as good
// and cheaper: measured (docs/performance.md, "Sampling triangle lights"),
// the Cornell box's light (about 0.02 sr per triangle from the floor) is
// sampled better per second by area, the spheres scene's large quad light
// (0.1–0.4 sr) by solid angle. Near 2π sr (x almost on the triangle)
// Arvo's formulas lose precision.
constexpr double kMinSphericalSolidAngle = 0.05;
constexpr double kMaxSphericalSolidAngle = 6.0;

bool sample_by_solid_angle(const SphericalTriangle& t) {
    return t.solid_angle >= kMinSphericalSolidAngle && t.solid_angle <= kMaxSphericalSolidAngle;
}

// The spherical triangle of p0 p1 p2 seen from x when it is to be sampled by
// solid angle, or an empty one (solid angle 0: sampled by area). The choice
// is made on the solid angle estimated from the centroid c, area · |cos θ_c|
// / |x − c|², in float: building the spherical triangle (double precision,
// atan2, asin) to decide was a tenth of the path-traced Cornell box's render
// instructions, for the 5 % of its shading points that see the light above
// kMinSphericalSolidAngle. Any choice that is a function of x and the
// triangle alone keeps the estimator unbiased, as long as sample_light and
// pdf_light_triangle make the same one.
SphericalTriangle spherical_triangle_to_sample(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 unit_normal, float area) {
    const Vec3 to_x = x - (1.0f / 3.0f) * (p0 + p1 + p2);
    const float dist2 = dot(to_x, to_x);
    const float cos_area = std::fabs(dot(unit_normal, to_x)) * area;  // |cos θ_c| · area · |x − c|
    if (!(cos_area >= static_cast<float>(kMinSphericalSolidAngle) * dist2 * std::sqrt(dist2))) return {};
    return make_spherical_triangle(x, p0, p1, p2);
}

// Solid-angle density of area-uniform sampling of a triangle of `area` at
// point y, seen from x: pdf_area · |x − y|² / |cos θ_y|; 0 edge-on.
float area_to_solid_angle(Vec3 x, Vec3 y, Vec3 unit_normal, float area) {
    const Vec3 d = x - y;
    const float dist2 = dot(d, d);
    if (!(dist2 > 0.0f)) return 0.0f;
    const float cos_y = std::fabs(dot(unit_normal, d)) / std::sqrt(dist2);
    if (!(cos_y > 0.0f)) return 0.0f;
    return dist2 / (cos_y * area);
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
    lights.environment = std::move(environment);
    lights.environment_lights = sample_environment_light && !is_black(lights.environment);
    if (lights.environment_lights) {
        float env_power = 0;
        if (has_map(lights.environment) || power.empty()) {
            const float r = bounding_radius(scene);
            env_power = std::max(environment_power_proxy(lights.environment), 1e-12f) * kPi * r * r;
        } else {
            // A constant environment is what BSDF sampling finds best (the
            // cosine lobe is its exact density on a diffuse surface); spending
            // light samples on it by power took half of the spheres scene's
            // and doubled its direct-light error (docs/performance.md). It
            // keeps a small share so that both strategies still count it.
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

    const Emitter e = lights.emitters[chosen];
    const auto [p0, p1, p2] = world_triangle_corners(scene, e.triangle, e.instance);
    const Vec3 n_w = normalize(cross(p1 - p0, p2 - p0));
    const SphericalTriangle spherical = spherical_triangle_to_sample(x, p0, p1, p2, n_w, lights.emitter_areas[chosen]);
    Vec3 y, wi;
    float pdf = 0;
    if (sample_by_solid_angle(spherical)) {
        // Uniform over the solid angle; the point is where that direction meets the plane.
        wi = sample_spherical_triangle(spherical, u1, u2);
        const float cos_y = dot(n_w, wi);
        const float t = dot(p0 - x, n_w) / cos_y;
        if (!(t > 0.0f) || !std::isfinite(t)) return false;
        y = x + t * wi;
        pdf = static_cast<float>(1.0 / spherical.solid_angle);
    } else {
        // Uniform by area: the square-root parameterisation of the triangle.
        const float su = std::sqrt(u1);
        const float b1 = 1.0f - su, b2 = u2 * su;
        y = (1.0f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
        const Vec3 to_light = y - x;
        const float dist2 = dot(to_light, to_light);
        if (!(dist2 > 0.0f)) return false;
        wi = to_light / std::sqrt(dist2);
        pdf = area_to_solid_angle(x, y, n_w, lights.emitter_areas[chosen]);
    }
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
    const float choice = lights.use_tree ? emitters_choice_probability(lights) *
                                               pmf_light_tree(lights.tree, x, n, static_cast<std::uint32_t>(e))
                                         : lights.choice_probability[e];
    if (!(choice > 0.0f)) return 0.0f;
    const auto [p0, p1, p2] = world_triangle_corners(scene, triangle, instance);
    const Vec3 n_w = normalize(cross(p1 - p0, p2 - p0));
    const SphericalTriangle spherical = spherical_triangle_to_sample(x, p0, p1, p2, n_w, lights.emitter_areas[e]);
    if (sample_by_solid_angle(spherical)) return choice * static_cast<float>(1.0 / spherical.solid_angle);
    return choice * area_to_solid_angle(x, y, n_w, lights.emitter_areas[e]);
}

LightKind light_kind(const LightSet& lights, const Scene& scene, std::uint32_t light) {
    if (light < lights.first_emitter()) {
        switch (lights.delta[light].type) {
            case LightType::Point: return LightKind::Point;
            case LightType::Spot: return LightKind::Spot;
            case LightType::Directional: return LightKind::Directional;
        }
    }
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
