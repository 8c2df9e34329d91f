#include "scene/quicklook.h"

#include <cmath>
#include <numbers>

#include "scene/mesh_file.h"

namespace sombra {

namespace {

constexpr float kFovDegrees = 40.0f;

// Radiance of a grey kd = 0.8 Lambertian surface facing the key light at the
// sphere's centre: L = I/d² · kd/π. 0.45 leaves headroom for light from the
// fill and rim lights overlapping it.
constexpr float kKeyRadiance = 0.45f;

struct Sphere {
    Vec3 centre;
    float radius;
};

Sphere bounding_sphere(const TriangleMesh& mesh) {
    Vec3 lo{INFINITY}, hi{-INFINITY};
    for (const Index3& tri : mesh.triangles)
        for (std::uint32_t v : tri) {
            lo = min(lo, mesh.positions[v]);
            hi = max(hi, mesh.positions[v]);
        }
    const float radius = 0.5f * length(hi - lo);
    // A single point (all triangles degenerate) still gets a usable frame.
    return {(lo + hi) * 0.5f, radius > 0.0f ? radius : 1.0f};
}

}  // namespace

Scene make_quicklook_scene(const std::filesystem::path& model, Diagnostics& diag) {
    LoadedMesh loaded = load_mesh_file(model, diag);
    const Sphere sphere = bounding_sphere(loaded.mesh);

    Scene scene;
    scene.background = Vec3{0.02f};
    scene.materials = std::move(loaded.materials);
    scene.geometry = std::move(loaded.mesh);

    // Far enough that the sphere fits the vertical field of view (the
    // horizontal one is wider for landscape images), with a 10 % margin.
    const float half_fov = kFovDegrees * 0.5f * std::numbers::pi_v<float> / 180.0f;
    const float distance = 1.1f * sphere.radius / std::sin(half_fov);
    const Vec3 view_dir = normalize(Vec3{0.0f, 0.35f, 1.0f});  // front, a little above
    scene.camera.look_at = CameraLookAt{sphere.centre + distance * view_dir, sphere.centre, Vec3{0, 1, 0}, kFovDegrees};

    // Three-point lighting around the camera, at a few radii from the model.
    auto light_at = [&](Vec3 direction, float distance_in_radii, float share) {
        const float d = distance_in_radii * sphere.radius;
        const float intensity = share * kKeyRadiance * std::numbers::pi_v<float> / 0.8f * d * d;
        return PointLight{sphere.centre + d * normalize(direction), Vec3{intensity}};
    };
    scene.lights.push_back(light_at({-1.0f, 1.4f, 1.3f}, 4.0f, 1.0f));   // key: upper left, front
    scene.lights.push_back(light_at({1.2f, 0.3f, 1.0f}, 4.0f, 0.35f));   // fill: right, low
    scene.lights.push_back(light_at({0.3f, 1.2f, -1.2f}, 4.0f, 0.5f));   // rim: behind, above
    return scene;
}

}  // namespace sombra
