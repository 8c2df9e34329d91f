#include "scene/animation.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "scene/scene.h"

namespace sombra {
namespace {

using Mat3 = std::array<double, 9>;  // row-major

Mat3 linear_of(const Transform& m) { return {m.m[0], m.m[1], m.m[2], m.m[4], m.m[5], m.m[6], m.m[8], m.m[9], m.m[10]}; }

double det(const Mat3& a) {
    return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) + a[2] * (a[3] * a[7] - a[4] * a[6]);
}

// The inverse transpose: cofactors over the determinant.
Mat3 inverse_transpose(const Mat3& a) {
    const double d = det(a);
    return {(a[4] * a[8] - a[5] * a[7]) / d, (a[5] * a[6] - a[3] * a[8]) / d, (a[3] * a[7] - a[4] * a[6]) / d,
            (a[2] * a[7] - a[1] * a[8]) / d, (a[0] * a[8] - a[2] * a[6]) / d, (a[1] * a[6] - a[0] * a[7]) / d,
            (a[1] * a[5] - a[2] * a[4]) / d, (a[2] * a[3] - a[0] * a[5]) / d, (a[0] * a[4] - a[1] * a[3]) / d};
}

Mat3 multiply(const Mat3& a, const Mat3& b) {
    Mat3 c{};
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) c[r * 3 + j] += a[r * 3 + k] * b[k * 3 + j];
    return c;
}

Mat3 transpose(const Mat3& a) { return {a[0], a[3], a[6], a[1], a[4], a[7], a[2], a[5], a[8]}; }

// Shepperd's method: the quaternion (x, y, z, w) of a proper rotation.
void quaternion_of(const Mat3& r, double q[4]) {
    const double trace = r[0] + r[4] + r[8];
    if (trace > 0) {
        const double s = 2 * std::sqrt(trace + 1);
        q[3] = s / 4;
        q[0] = (r[7] - r[5]) / s;
        q[1] = (r[2] - r[6]) / s;
        q[2] = (r[3] - r[1]) / s;
    } else if (r[0] > r[4] && r[0] > r[8]) {
        const double s = 2 * std::sqrt(1 + r[0] - r[4] - r[8]);
        q[3] = (r[7] - r[5]) / s;
        q[0] = s / 4;
        q[1] = (r[1] + r[3]) / s;
        q[2] = (r[2] + r[6]) / s;
    } else if (r[4] > r[8]) {
        const double s = 2 * std::sqrt(1 + r[4] - r[0] - r[8]);
        q[3] = (r[2] - r[6]) / s;
        q[0] = (r[1] + r[3]) / s;
        q[1] = s / 4;
        q[2] = (r[5] + r[7]) / s;
    } else {
        const double s = 2 * std::sqrt(1 + r[8] - r[0] - r[4]);
        q[3] = (r[3] - r[1]) / s;
        q[0] = (r[2] + r[6]) / s;
        q[1] = (r[5] + r[7]) / s;
        q[2] = s / 4;
    }
}

Mat3 rotation_of(const double q[4]) {
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    return {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
            2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
            2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
}

// Spherical interpolation of unit quaternions along the shorter arc.
void slerp(const double a[4], const double b_in[4], double u, double out[4]) {
    double b[4] = {b_in[0], b_in[1], b_in[2], b_in[3]};
    double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (c < 0) {
        for (double& v : b) v = -v;
        c = -c;
    }
    double wa = 1 - u, wb = u;
    // Nearly equal: the linear blend, renormalised, is as exact and cannot divide by sin θ ≈ 0.
    if (c < 0.9995) {
        const double theta = std::acos(c), s = std::sin(theta);
        wa = std::sin((1 - u) * theta) / s;
        wb = std::sin(u * theta) / s;
    }
    double len = 0;
    for (int k = 0; k < 4; ++k) {
        out[k] = wa * a[k] + wb * b[k];
        len += out[k] * out[k];
    }
    len = std::sqrt(len);
    for (int k = 0; k < 4; ++k) out[k] /= len;
}

double lerp(double a, double b, double u) { return a + (b - a) * u; }

// The pair of keys around `time` and the weight of the later one; a single
// key (u = 0) outside the keys' range or exactly on a key.
template <class Key>
std::pair<std::size_t, double> bracket(std::span<const Key> keys, double time) {
    if (time <= keys.front().time) return {0, 0.0};
    if (time >= keys.back().time) return {keys.size() - 1, 0.0};
    const auto it = std::upper_bound(keys.begin(), keys.end(), time, [](double t, const Key& k) { return t < k.time; });
    const auto i = static_cast<std::size_t>(it - keys.begin()) - 1;
    if (time == keys[i].time) return {i, 0.0};
    return {i, (time - keys[i].time) / (keys[i + 1].time - keys[i].time)};
}

}  // namespace

PolarParts polar_decompose(const Transform& m) {
    PolarParts parts{};
    for (int r = 0; r < 3; ++r) parts.translation[r] = m.m[r * 4 + 3];
    const Mat3 a = linear_of(m);
    // Newton's iteration Q ← (Q + Q⁻ᵀ)/2 converges to the orthogonal factor.
    Mat3 q = a;
    for (int i = 0; i < 100; ++i) {
        const Mat3 inv_t = inverse_transpose(q);
        double change = 0;
        for (int k = 0; k < 9; ++k) {
            const double next = 0.5 * (q[k] + inv_t[k]);
            change = std::max(change, std::fabs(next - q[k]));
            q[k] = next;
        }
        if (change < 1e-14) break;
    }
    Mat3 s = multiply(transpose(q), a);
    // A reflection goes to S, so that R is a rotation: (−Q)(−S) = Q·S.
    if (det(q) < 0)
        for (int k = 0; k < 9; ++k) {
            q[k] = -q[k];
            s[k] = -s[k];
        }
    quaternion_of(q, parts.rotation);
    std::copy(s.begin(), s.end(), parts.stretch);
    return parts;
}

Transform compose_polar(const PolarParts& parts) {
    Mat3 s;
    std::copy(parts.stretch, parts.stretch + 9, s.begin());
    const Mat3 rs = multiply(rotation_of(parts.rotation), s);
    Transform t;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) t.m[r * 4 + c] = static_cast<float>(rs[r * 3 + c]);
        t.m[r * 4 + 3] = static_cast<float>(parts.translation[r]);
    }
    return t;
}

Transform interpolate_transform(std::span<const TransformKey> keys, double time) {
    const auto [i, u] = bracket(keys, time);
    if (u == 0.0) return keys[i].transform;
    const PolarParts a = polar_decompose(keys[i].transform), b = polar_decompose(keys[i + 1].transform);
    PolarParts out{};
    for (int k = 0; k < 3; ++k) out.translation[k] = lerp(a.translation[k], b.translation[k], u);
    for (int k = 0; k < 9; ++k) out.stretch[k] = lerp(a.stretch[k], b.stretch[k], u);
    slerp(a.rotation, b.rotation, u, out.rotation);
    return compose_polar(out);
}

CameraSpec interpolate_camera(std::span<const CameraKey> keys, double time) {
    const auto [i, weight] = bracket(keys, time);
    const double u = weight;  // a plain variable: lambdas may not capture a structured binding (C++17)
    const CameraKey& a = keys[i];
    const CameraKey& b = u == 0.0 ? a : keys[i + 1];
    const auto mix = [u](float x, float y) { return static_cast<float>(lerp(x, y, u)); };
    const auto mix3 = [&](Vec3 x, Vec3 y) { return Vec3{mix(x.x, y.x), mix(x.y, y.y), mix(x.z, y.z)}; };
    CameraSpec camera;
    camera.look_at = CameraLookAt{mix3(a.origin, b.origin), mix3(a.look_at, b.look_at), mix3(a.up, b.up),
                                  mix(a.fov_degrees, b.fov_degrees)};
    camera.aperture_radius = mix(a.aperture_radius, b.aperture_radius);
    if (a.focus_distance && b.focus_distance) camera.focus_distance = mix(*a.focus_distance, *b.focus_distance);
    return camera;
}

namespace {

// "NAME: " for an error about part NAME of the scene, or nothing when the
// part is the scene itself (a glTF file's quick look).
std::string part_name(const std::string& scene_name, const std::string& name) {
    return name.empty() || name == scene_name ? std::string() : name + ": ";
}

}  // namespace

void set_scene_time(Scene& scene, double time, const std::string& scene_name) {
    if (!scene.animation) return;
    const SceneAnimation& animation = *scene.animation;
    // A glTF file's parts share its animation: its nodes are evaluated once.
    const GltfNodeAnimation* evaluated = nullptr;
    std::vector<Transform> worlds;
    const auto node_worlds = [&](const GltfNodeAnimation& gltf) -> const std::vector<Transform>& {
        if (&gltf != evaluated) {
            worlds = gltf_node_worlds(gltf, time);
            evaluated = &gltf;
        }
        return worlds;
    };
    for (const AnimatedObject& object : animation.objects) {
        const Transform keyed = interpolate_transform(object.keys, time);
        if (object.gltf) node_worlds(*object.gltf);
        for (std::size_t k = 0; k < object.after.size(); ++k) {
            Instance& instance = scene.instances[object.first_instance + k];
            const Transform node = object.gltf ? compose(object.before[k], worlds[object.nodes[k]]) : object.before[k];
            if (place_instance(instance, compose(compose(node, keyed), object.after[k]))) {
                // A grid inside the object moves with its transform, not with a node of its file (spec §26).
                if (instance.interior == kNoMedium || !scene.media[instance.interior].density) continue;
                if (place_grid_medium(scene.media[instance.interior], compose(keyed, object.after[k]))) continue;
                throw Error(scene_name, object.name + "/interior: at " + std::to_string(time) +
                                            " s the grid's and the object's transforms together are not invertible");
            }
            if (object.gltf)
                throw Error(scene_name, object.name + ": " + object.file + ": node " + std::to_string(object.nodes[k]) +
                                            ": at " + std::to_string(time) +
                                            " s the animated transform is not invertible");
            throw Error(scene_name, object.name + "/transform: at " + std::to_string(time) +
                                        " s the interpolated transform is not invertible");
        }
    }
    for (const AnimatedLight& moving : animation.lights) {
        Transform world = moving.gltf ? node_worlds(*moving.gltf)[moving.node] : Transform{};
        if (!moving.keys.empty()) world = compose(world, interpolate_transform(moving.keys, time));
        PunctualLight light = moving.local;
        if (transform_light(light, compose(world, moving.after)) != LightPlacement::Ok)
            throw Error(scene_name, part_name(scene_name, moving.name) +
                                        (moving.gltf ? "node " + std::to_string(moving.node) + ": " : "") + "at " +
                                        std::to_string(time) + " s its light's placement is not finite");
        scene.lights[moving.light] = light;
    }
    if (animation.node_camera && scene.camera.look_at) {
        const AnimatedCamera& c = *animation.node_camera;
        CameraLookAt& view = *scene.camera.look_at;
        Vec3 forward;
        if (!gltf_camera_frame(node_worlds(*c.gltf)[c.node], view.origin, forward, view.up))
            throw Error(scene_name, part_name(scene_name, c.file) + "node " + std::to_string(c.node) + ": at " +
                                        std::to_string(time) +
                                        " s the camera's node has no frame (scaled to nothing, or not finite)");
        view.look_at = view.origin + forward;
    }
    if (animation.camera.empty()) return;
    const CameraSpec camera = interpolate_camera(animation.camera, time);
    const std::pair projection{scene.camera.projection, scene.camera.ortho_half_height};
    // Each key was checked as a camera; a blend of two can still lose its
    // frame (look_at meeting origin, up turning along the view): refused
    // as the scene file's reader refuses such a key (1e-3 of parallel).
    const CameraLookAt& c = *camera.look_at;
    const Vec3 view = c.look_at - c.origin;
    const float cross_len = length(cross(c.up, view)), scale = length(c.up) * length(view);
    if (!(scale > 0.0f) || !(cross_len > 1e-3f * scale))
        throw Error(scene_name, "/camera: at " + std::to_string(time) +
                                    " s the blended camera has no frame (look_at meets origin, or up lies along "
                                    "the view)");
    scene.camera = camera;
    // Keys are look-at cameras; the projection stays the scene's own.
    scene.camera.projection = projection.first;
    scene.camera.ortho_half_height = projection.second;
}

}  // namespace sombra
