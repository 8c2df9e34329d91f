// Questions about a loaded scene's content that the app asks before rendering.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "scene/scene.h"

namespace sombra {

bool needs_path_integrator(const Scene& scene) {
    if (scene.environment) return true;
    std::vector<bool> used(scene.materials.size(), false);
    for (const std::uint32_t id : scene.geometry.material_ids)
        if (id < used.size()) used[id] = true;
    for (const TriangleMesh& mesh : scene.instanced_meshes)
        for (const std::uint32_t id : mesh.material_ids)
            if (id < used.size()) used[id] = true;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        if (!used[i]) continue;
        if (m.emits_front_only || m.type == MaterialType::Mirror || m.type == MaterialType::Dielectric) return true;
    }
    return false;
}

const SceneObject* object_of_triangle(const Scene& scene, std::uint32_t triangle) {
    // Objects are in triangle order: the last one starting at or before `triangle`.
    const auto it = std::upper_bound(scene.objects.begin(), scene.objects.end(), triangle,
                                     [](std::uint32_t t, const SceneObject& o) { return t < o.first_triangle; });
    if (it == scene.objects.begin()) return nullptr;
    const SceneObject& object = *(it - 1);
    return triangle - object.first_triangle < object.triangle_count ? &object : nullptr;
}

bool uses_media(const Scene& scene) {
    if (starting_medium(scene) != kNoMedium) return true;
    return std::any_of(scene.objects.begin(), scene.objects.end(), [](const SceneObject& o) {
        return o.bounds_medium && (o.interior != kNoMedium || o.exterior != kNoMedium);
    });
}

const SceneObject* object_of_surface(const Scene& scene, std::uint32_t triangle, std::uint32_t instance) {
    return instance == kNoInstance ? object_of_triangle(scene, triangle)
                                   : &scene.objects[scene.instances[instance].object];
}

namespace {

// The inverse of `m` when m is invertible in float (a finite, non-zero
// determinant and a finite inverse), for place_instance and place_grid_medium.
std::optional<Transform> float_inverse(const Transform& m) {
    const float det = determinant3(m);
    if (!(det != 0.0f) || !std::isfinite(det)) return std::nullopt;
    const Transform inverse = inverse_affine(m);
    for (const float v : inverse.m)
        if (!std::isfinite(v)) return std::nullopt;
    return inverse;
}

}  // namespace

bool place_instance(Instance& instance, const Transform& object_to_world) {
    const std::optional<Transform> to_object = float_inverse(object_to_world);
    if (!to_object) return false;
    instance.object_to_world = object_to_world;
    instance.world_to_object = *to_object;
    instance.normal_to_world = normal_transform(object_to_world);
    instance.mirrored = determinant3(object_to_world) < 0.0f;
    return true;
}

bool place_grid_medium(Medium& medium, const Transform& object_to_world) {
    const std::optional<Transform> to_grid = float_inverse(compose(medium.density->index_to_world, object_to_world));
    if (!to_grid) return false;
    medium.world_to_grid = *to_grid;
    return true;
}

std::uint64_t stored_triangle_count(const Scene& scene) {
    std::uint64_t count = scene.geometry.triangle_count();
    for (const TriangleMesh& mesh : scene.instanced_meshes) count += mesh.triangle_count();
    return count;
}

std::uint64_t drawn_triangle_count(const Scene& scene) {
    std::uint64_t count = scene.geometry.triangle_count();
    for (const Instance& instance : scene.instances) count += scene.instanced_meshes[instance.mesh].triangle_count();
    return count;
}

bool emits_light(const Scene& scene) {
    if (std::any_of(scene.lights.begin(), scene.lights.end(),
                    [](const PunctualLight& l) { return max_component(l.intensity) > 0.0f; }))
        return true;
    if (std::any_of(scene.media.begin(), scene.media.end(),
                    [](const Medium& m) { return max_component(m.emission) > 0.0f; }))
        return true;
    if (scene.environment) {
        const EnvironmentMap& env = *scene.environment;
        if (env.scale > 0.0f &&
            std::any_of(env.image.rgb.begin(), env.image.rgb.end(), [](float v) { return v > 0.0f; }))
            return true;
    } else if (max_component(scene.background) > 0.0f) {
        return true;
    }
    // An emissive material counts only where some triangle wears it.
    std::vector<bool> emissive(scene.materials.size());
    bool any = false;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) any |= (emissive[i] = is_emissive(scene.materials[i]));
    if (!any) return false;
    const auto wears = [&emissive](const TriangleMesh& mesh) {
        return std::any_of(mesh.material_ids.begin(), mesh.material_ids.end(),
                           [&emissive](std::uint32_t id) { return id < emissive.size() && emissive[id]; });
    };
    return wears(scene.geometry) || std::any_of(scene.instanced_meshes.begin(), scene.instanced_meshes.end(), wears);
}

}  // namespace sombra
