// Animation (spec §22): keyframed object transforms and cameras on one
// clock, and the scene at a moment of it. Keys hold whole matrices; between
// two keys each is split by polar decomposition M = T·R·S (R a rotation, S
// symmetric and carrying any reflection, as pbrt-v4's AnimatedTransform), T
// and S are interpolated linearly and R by slerp along the shorter arc.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "scene/gltf_animation.h"
#include "scene/light.h"
#include "scene/transform.h"

namespace sombra {

struct Scene;
struct CameraSpec;

struct TransformKey {
    double time = 0;  // seconds
    Transform transform;
};

// A look-at camera at one moment (spec §22: each key a full camera object).
struct CameraKey {
    double time = 0;
    Vec3 origin, look_at;
    Vec3 up{0, 1, 0};
    float fov_degrees = 45;
    float aperture_radius = 0;
    std::optional<float> focus_distance;
};

// An object whose transform is keyed, or a glTF part whose nodes are
// animated: it is stored as instanced meshes (scene/scene.h) so that a new
// moment moves its instances and keeps its meshes' structures. Its instance
// k (Scene::instances[first_instance + k]) is before[k], then (with `gltf`)
// node nodes[k]'s world transform at that moment, then the keyed
// transform, then after[k]: a glTF file's own placement of the mesh (with
// `gltf`: EXT_mesh_gpu_instancing's, before the node), the object's
// transform, and its "instances" entry.
struct AnimatedObject {
    std::string name;  // the scene file's pointer, for messages
    std::uint32_t first_instance = 0;
    std::vector<TransformKey> keys;  // times increasing, at least one
    std::vector<Transform> before, after;
    std::shared_ptr<const GltfNodeAnimation> gltf{};  // none: no glTF animation
    std::vector<std::uint32_t> nodes{};               // with `gltf`: one per instance
    std::string file{};                               // with `gltf`: the glTF file, for messages
};

// A light a model file places on something that moves (spec §22): a glTF
// light whose node is animated, or any light of a scene object whose
// transform is keyed. At each moment `local` is carried by its node's world
// transform (with `gltf`; without, `local` is in the file's coordinates),
// then the object's keyed transform (none: `keys` empty), then `after` (the
// object's fixed transform and "instances" entry), into Scene::lights[light].
struct AnimatedLight {
    std::uint32_t light = 0;
    PunctualLight local;
    std::shared_ptr<const GltfNodeAnimation> gltf{};
    std::uint32_t node = 0;
    std::vector<TransformKey> keys{};
    Transform after{};
    std::string name{};  // for messages: the file, or the object's pointer
};

// The camera a glTF node carries when the node is animated (the quick look
// of a glTF file): at each moment it stands at the node's origin, looking
// along the node's −z with its +y up; the field of view stays the scene
// camera's.
struct AnimatedCamera {
    std::shared_ptr<const GltfNodeAnimation> gltf;
    std::uint32_t node = 0;
    std::string file;  // for messages
};

struct SceneAnimation {
    double fps = 24;
    std::int64_t first_frame = 0, last_frame = 0;
    std::vector<AnimatedObject> objects;
    std::vector<CameraKey> camera;  // empty: the camera does not move
    std::vector<AnimatedLight> lights{};
    std::optional<AnimatedCamera> node_camera{};  // never with `camera` keys
};

// The keyed transform at `time`: the end keys hold outside their range.
Transform interpolate_transform(std::span<const TransformKey> keys, double time);

// The camera at `time`, each keyed value interpolated linearly.
CameraSpec interpolate_camera(std::span<const CameraKey> keys, double time);

// The polar decomposition of `m`'s linear part, R·S, with R a proper
// rotation as a unit quaternion (x, y, z, w) and S symmetric (row-major 3×3).
struct PolarParts {
    double translation[3];
    double rotation[4];
    double stretch[9];
};
PolarParts polar_decompose(const Transform& m);
Transform compose_polar(const PolarParts& parts);

// Moves `scene` to `time` seconds: its animated objects' instances, its
// lights that move and its camera. Throws Error(scene_name, …) naming the
// object (and the glTF node) whose transform at that moment cannot be
// inverted, or whose light or camera loses its placement.
void set_scene_time(Scene& scene, double time, const std::string& scene_name);

}  // namespace sombra
