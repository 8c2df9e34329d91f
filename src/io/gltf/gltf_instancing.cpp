// Node transforms and EXT_mesh_gpu_instancing (spec §23, §24): T · R · S
// matrices, and a node's instances read from its accessors with every
// claim checked before it sizes an allocation.
#include <cmath>
#include <string>

#include "io/gltf/gltf.h"
#include "scene/scene_builder.h"

namespace sombra::gltf {

std::optional<Transform> trs_transform(Vec3 translation, double x, double y, double z, double w, Vec3 scale) {
    const double len = std::sqrt(x * x + y * y + z * z + w * w);
    if (!(len > 1e-12) || !std::isfinite(len)) return std::nullopt;
    x /= len, y /= len, z /= len, w /= len;
    // Rotation matrix of the unit quaternion (x, y, z, w), columns scaled by s.
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    const float s[3] = {scale.x, scale.y, scale.z};
    const float t[3] = {translation.x, translation.y, translation.z};
    Transform out;
    for (std::size_t row = 0; row < 3; ++row) {
        for (std::size_t col = 0; col < 3; ++col) out.m[row * 4 + col] = float(r[row][col]) * s[col];
        out.m[row * 4 + 3] = t[row];
    }
    return out;
}

std::vector<Transform> gpu_instances(const AccessorReader& r, const tinygltf::Node& node, int index, std::size_t room) {
    const auto it = node.extensions.find(kGpuInstancing);
    if (it == node.extensions.end()) return {};
    const std::string where = "node " + std::to_string(index);
    const auto fail = [&](const std::string& what) {
        throw Error(r.file, where + ": " + kGpuInstancing + ": " + what);
    };
    if (node.mesh < 0) fail("the node has no mesh to instance");
    const tinygltf::Value& ext = it->second;
    if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
        fail("'attributes' must be an object");
    const tinygltf::Value& attributes = ext.Get("attributes");
    if (attributes.Keys().empty()) fail("'attributes' is empty");

    // Every attribute (custom ones too) has one element per instance.
    constexpr const char* kNames[3] = {"TRANSLATION", "ROTATION", "SCALE"};
    int accessor[3] = {-1, -1, -1};
    std::size_t count = 0;
    std::string first;
    for (const std::string& name : attributes.Keys()) {
        const std::optional<int> a = value_int(attributes.Get(name), 0, 1 << 30);
        if (!a) fail(name + " is not an accessor index");
        const std::string what = name + " of " + where;
        const std::size_t n = accessor_count(r, *a, what);
        if (first.empty()) {
            first = name;
            count = n;
        } else if (n != count) {
            fail(first + " has " + std::to_string(count) + " elements but " + name + " has " + std::to_string(n));
        }
        for (int k = 0; k < 3; ++k)
            if (name == kNames[k]) accessor[k] = *a;
    }
    // Data behind the count bounds it by the file's bytes (an accessor
    // without a bufferView is all zeros, of any count).
    bool backed = false;
    for (const int a : accessor) backed = backed || (a >= 0 && r.model.accessors[std::size_t(a)].bufferView >= 0);
    if (!backed) fail("needs TRANSLATION, ROTATION or SCALE with a bufferView");
    if (count > room)
        fail(std::to_string(count) + " instances would take the file past " + std::to_string(kMaxInstances));

    const auto read = [&](int k, Semantic semantic) {
        return accessor[k] < 0 ? std::vector<float>{}
                               : read_floats(r, accessor[k], semantic, std::string(kNames[k]) + " of " + where);
    };
    const std::vector<float> t = read(0, Semantic::Position);
    const std::vector<float> q = read(1, Semantic::Rotation);
    const std::vector<float> s = read(2, Semantic::Position);
    std::vector<Transform> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const std::string instance = "instance " + std::to_string(i) + ": ";
        const Vec3 translation = t.empty() ? Vec3{0.0f} : Vec3{t[3 * i], t[3 * i + 1], t[3 * i + 2]};
        const Vec3 scale = s.empty() ? Vec3{1.0f} : Vec3{s[3 * i], s[3 * i + 1], s[3 * i + 2]};
        // A zero scale draws nothing and has no inverse for the ray transform.
        if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f)
            fail(instance + "SCALE has a zero component: the transform is not invertible");
        const std::optional<Transform> m =
            q.empty() ? trs_transform(translation, 0, 0, 0, 1, scale)
                      : trs_transform(translation, q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3], scale);
        if (!m) fail(instance + "ROTATION is not a unit quaternion");
        out.push_back(*m);
    }
    return out;
}

}  // namespace sombra::gltf
