// The quick look of spec §7: a scene made on the fly for a lone model file,
// framed and lit so that any model shows (or placed as its glTF file says).
#include "io/quicklook.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "core/image_limits.h"
#include "io/mesh_file.h"
#include "scene/scene_builder.h"

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

// The box of the model's triangles, its instanced meshes' boxes placed by
// each instance (their corners: the box of the placed box, a little larger).
Sphere bounding_sphere(const LoadedMesh& model) {
    Vec3 lo{INFINITY}, hi{-INFINITY};
    const auto box = [](const TriangleMesh& mesh, Vec3& low, Vec3& high) {
        for (const Index3& tri : mesh.triangles)
            for (std::uint32_t v : tri) {
                low = min(low, mesh.positions[v]);
                high = max(high, mesh.positions[v]);
            }
    };
    box(model.mesh, lo, hi);
    for (const InstancedPart& part : model.instanced) {
        Vec3 part_lo{INFINITY}, part_hi{-INFINITY};
        box(part.mesh, part_lo, part_hi);
        if (!(part_lo.x <= part_hi.x)) continue;
        for (const Transform& t : part.instances)
            for (int corner = 0; corner < 8; ++corner) {
                const Vec3 c{corner & 1 ? part_hi.x : part_lo.x, corner & 2 ? part_hi.y : part_lo.y,
                             corner & 4 ? part_hi.z : part_lo.z};
                const Vec3 p = transform_point(t, c);
                lo = min(lo, p);
                hi = max(hi, p);
            }
    }
    const float radius = 0.5f * length(hi - lo);
    // A single point (all triangles degenerate) still gets a usable frame.
    return {(lo + hi) * 0.5f, radius > 0.0f ? radius : 1.0f};
}

}  // namespace

LoadedScene make_quicklook_scene(const std::filesystem::path& model, Diagnostics& diag) {
    LoadedMesh loaded = load_mesh_file(model, diag);
    const Sphere sphere = bounding_sphere(loaded);

    LoadedScene out;
    SceneBuilder builder;
    builder.set_background(Vec3{0.02f});
    // The model is the world, in its own coordinates: it moves in as it is.
    const MeshPlacement placement{model.filename().string(), model.string(), std::nullopt, std::nullopt};
    // Meshes drawn several times are stored once (spec §23); their errors
    // name the node that placed the instance. Parts the file animates
    // follow its nodes (spec §22): all its animations at 24 fps, frames 0
    // to the last key time × 24 rounded up.
    std::optional<SceneAnimation> animation;
    if (loaded.animation)
        animation = SceneAnimation{
            24.0, 0, static_cast<std::int64_t>(std::ceil(std::min(loaded.animation->end_time, 1e6) * 24.0)), {}, {}};
    for (const InstancedPart& part : loaded.instanced) {
        if (animation && !part.nodes.empty())
            animation->objects.push_back(AnimatedObject{model.filename().string(),
                                                        static_cast<std::uint32_t>(builder.scene().instances.size()),
                                                        {TransformKey{}},
                                                        part.local,
                                                        std::vector<Transform>(part.local.size()),
                                                        loaded.animation,
                                                        part.nodes,
                                                        model.string()});
        std::size_t bad = 0;
        switch (
            builder.add_instanced_mesh(part.mesh, loaded.materials, loaded.textures, placement, part.instances, &bad)) {
            case MeshProblem::None: continue;
            case MeshProblem::BadVertexIndex: break;
            case MeshProblem::NonFinitePlacement:
                throw Error(model.string(), instance_name(part, bad) + ": a transformed vertex is not finite");
            case MeshProblem::SingularInstance:
                throw Error(model.string(), instance_name(part, bad) + ": the transform is not invertible");
            case MeshProblem::TooManyInstances:
                throw Error(model.string(), "more than " + std::to_string(kMaxInstances) + " instances");
        }
        throw Error(model.string(), "a triangle refers to a vertex that does not exist");
    }
    if ((!loaded.mesh.triangles.empty() || loaded.instanced.empty()) &&
        builder.add_mesh(std::move(loaded.mesh), std::move(loaded.materials), std::move(loaded.textures), placement) !=
            MeshProblem::None)
        throw Error(model.string(), "a triangle refers to a vertex that does not exist");

    // A glTF file's own camera (its first) and point lights replace the
    // automatic framing and lighting; its aspect ratio sets the image's
    // height for the default width.
    CameraSpec camera;
    if (loaded.camera) {
        const ModelCamera& c = *loaded.camera;
        camera.look_at = CameraLookAt{c.origin, c.origin + c.forward, c.up, c.yfov_degrees};
        if (c.ymag > 0) {
            camera.projection = CameraSpec::Projection::Orthographic;
            camera.ortho_half_height = c.ymag;
        }
        if (c.aspect > 0) {
            const float height = std::round(static_cast<float>(out.settings.width) / c.aspect);
            out.settings.height = static_cast<int>(std::clamp(height, 1.0f, static_cast<float>(kMaxImageSide)));
        }
    }
    for (std::size_t i = 0; i < loaded.lights.size(); ++i) {
        // Lights and the camera on animated nodes follow them (spec §22).
        if (animation && i < loaded.light_nodes.size() && loaded.light_nodes[i] >= 0)
            animation->lights.push_back(AnimatedLight{static_cast<std::uint32_t>(builder.scene().lights.size()),
                                                      loaded.lights_in_nodes[i],
                                                      loaded.animation,
                                                      static_cast<std::uint32_t>(loaded.light_nodes[i]),
                                                      {},
                                                      {},
                                                      model.string()});
        builder.add_light(loaded.lights[i]);
    }
    if (animation && loaded.camera && loaded.camera_node >= 0)
        animation->node_camera =
            AnimatedCamera{loaded.animation, static_cast<std::uint32_t>(loaded.camera_node), model.string()};

    // Far enough that the sphere fits the vertical field of view (the
    // horizontal one is wider for landscape images), with a 10 % margin.
    const float half_fov = kFovDegrees * 0.5f * std::numbers::pi_v<float> / 180.0f;
    const float distance = 1.1f * sphere.radius / std::sin(half_fov);
    // A three-quarter view from the front (+z, glTF's and most OBJ files'
    // front) and its left, 24° above: the Stanford bunny and dragon, which
    // face −x, show their heads, and boxy models show three faces.
    const Vec3 view_dir = normalize(Vec3{-0.5f, 0.45f, 0.9f});
    if (!camera.look_at)
        camera.look_at = CameraLookAt{sphere.centre + distance * view_dir, sphere.centre, Vec3{0, 1, 0}, kFovDegrees};
    builder.set_camera(camera);
    if (!loaded.lights.empty()) {
        out.scene = builder.finish();
        out.scene.animation = std::move(animation);
        return out;
    }

    // Three-point lighting around the camera, at a few radii from the model.
    auto light_at = [&](Vec3 direction, float distance_in_radii, float share) {
        const float d = distance_in_radii * sphere.radius;
        const float intensity = share * kKeyRadiance * std::numbers::pi_v<float> / 0.8f * d * d;
        return make_point_light(sphere.centre + d * normalize(direction), Vec3{intensity});
    };
    builder.add_light(light_at({-1.0f, 1.4f, 1.3f}, 4.0f, 1.0f));  // key: upper left, front
    builder.add_light(light_at({1.2f, 0.3f, 1.0f}, 4.0f, 0.35f));  // fill: right, low
    builder.add_light(light_at({0.3f, 1.2f, -1.2f}, 4.0f, 0.5f));  // rim: behind, above
    out.scene = builder.finish();
    out.scene.animation = std::move(animation);
    return out;
}

}  // namespace sombra
