// glTF animations (spec §22, glTF 2.0 §3.11): every animation's
// translation, rotation and scale channels, read into one plain-data
// GltfNodeAnimation that set_scene_time evaluates. All of a file's
// animations play together on the scene's clock.
#include <cmath>
#include <map>
#include <utility>

#include "io/gltf/gltf.h"

namespace sombra::gltf {

namespace {

// Key values kept for all samplers: samplers may share one accessor, so the
// file's bytes alone do not bound what reading each of them costs.
constexpr std::size_t kMaxKeyValues = std::size_t{1} << 26;

GltfNodeAnimation::Node rest_of(const tinygltf::Node& n, int parent) {
    GltfNodeAnimation::Node out;
    out.parent = parent;
    if (n.matrix.size() == 16) {
        out.has_matrix = true;
        for (std::size_t row = 0; row < 4; ++row)
            for (std::size_t col = 0; col < 4; ++col) out.matrix.m[row * 4 + col] = float(n.matrix[col * 4 + row]);
        return out;
    }
    for (std::size_t k = 0; k < 3 && n.translation.size() == 3; ++k) out.translation[k] = n.translation[k];
    for (std::size_t k = 0; k < 4 && n.rotation.size() == 4; ++k) out.rotation[k] = n.rotation[k];
    for (std::size_t k = 0; k < 3 && n.scale.size() == 3; ++k) out.scale[k] = n.scale[k];
    return out;
}

// Sampler `index` of `animation`, read for a rotation or a 3-vector.
GltfSampler read_sampler(const AccessorReader& r, const tinygltf::Animation& animation, int index, bool rotation,
                         const std::string& where, std::size_t& budget) {
    const tinygltf::AnimationSampler& s = animation.samplers[std::size_t(index)];
    const auto fail = [&](const std::string& what) { throw Error(r.file, where + ": " + what); };
    GltfSampler out;
    if (s.interpolation == "LINEAR")
        out.interpolation = GltfSampler::Interpolation::Linear;
    else if (s.interpolation == "STEP")
        out.interpolation = GltfSampler::Interpolation::Step;
    else if (s.interpolation == "CUBICSPLINE")
        out.interpolation = GltfSampler::Interpolation::CubicSpline;
    else
        fail("unknown interpolation '" + s.interpolation + "' (LINEAR, STEP or CUBICSPLINE)");
    if (s.input < 0) fail("has no input accessor");
    if (s.output < 0) fail("has no output accessor");
    // Counted before anything is read.
    const std::size_t in = accessor_count(r, s.input, where + " input");
    const std::size_t out_count = accessor_count(r, s.output, where + " output");
    if (in > budget || out_count > budget / 4 || in + out_count * 4 > budget)
        fail("the file's animations hold more than " + std::to_string(kMaxKeyValues) + " key values");
    budget -= in + out_count * 4;
    out.times = read_floats(r, s.input, Semantic::KeyTimes, where + " input");
    if (out.times.empty()) fail("the input has no key times");
    for (std::size_t k = 1; k < out.times.size(); ++k)
        if (!(out.times[k] > out.times[k - 1]))
            fail("key times must increase: element " + std::to_string(k) + " (" + std::to_string(out.times[k]) +
                 ") follows " + std::to_string(out.times[k - 1]));
    out.components = rotation ? 4 : 3;
    out.values = read_floats(r, s.output, rotation ? Semantic::KeyRotation : Semantic::KeyVector, where + " output");
    const bool cubic = out.interpolation == GltfSampler::Interpolation::CubicSpline;
    const std::size_t keys = out.times.size(), want = cubic ? 3 * keys : keys;
    const std::size_t got = out.values.size() / std::size_t(out.components);
    if (got != want)
        fail("the output has " + std::to_string(got) + " elements for " + std::to_string(keys) + " key times (" +
             (cubic ? "CUBICSPLINE needs 3 per key" : "one per key is needed") + ")");
    if (rotation)
        for (std::size_t k = 0; k < keys; ++k) {
            const float* q = &out.values[(cubic ? 3 * k + 1 : k) * 4];
            if (!(std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] + double(q[3]) * q[3]) >
                  1e-6))
                fail("key " + std::to_string(k) + " is not a unit quaternion");
        }
    return out;
}

}  // namespace

std::shared_ptr<GltfNodeAnimation> read_animations(const AccessorReader& r, const std::vector<std::uint32_t>& order,
                                                   std::map<std::string, std::size_t>& skipped) {
    const tinygltf::Model& model = r.model;
    if (model.animations.empty()) return nullptr;
    auto out = std::make_shared<GltfNodeAnimation>();
    const std::size_t count = model.nodes.size();
    std::size_t budget = kMaxKeyValues;
    std::vector<int> parent(count, -1);  // the loader's walk checked the tree
    for (std::size_t i = 0; i < count; ++i)
        for (const int child : model.nodes[i].children)
            if (child >= 0 && std::size_t(child) < count) parent[std::size_t(child)] = int(i);
    out->nodes.reserve(count);
    for (std::size_t i = 0; i < count; ++i) out->nodes.push_back(rest_of(model.nodes[i], parent[i]));
    out->order = order;

    for (std::size_t a = 0; a < model.animations.size(); ++a) {
        const tinygltf::Animation& animation = model.animations[a];
        const std::string name = "animation " + std::to_string(a);
        std::map<std::pair<int, bool>, std::uint32_t> read;  // (sampler, rotation) → index in out->samplers
        for (std::size_t c = 0; c < animation.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = animation.channels[c];
            const std::string where = name + ": channel " + std::to_string(c);
            const auto fail = [&](const std::string& what) { throw Error(r.file, where + ": " + what); };
            if (channel.sampler < 0 || std::size_t(channel.sampler) >= animation.samplers.size())
                fail("sampler " + std::to_string(channel.sampler) + " does not exist (the animation has " +
                     std::to_string(animation.samplers.size()) + ")");
            const std::string& path = channel.target_path;
            GltfChannel::Path kind;
            if (path == "translation")
                kind = GltfChannel::Path::Translation;
            else if (path == "rotation")
                kind = GltfChannel::Path::Rotation;
            else if (path == "scale")
                kind = GltfChannel::Path::Scale;
            else if (path == "weights" || path == "pointer") {
                ++skipped[path == "weights" ? "animations of morph target weights" : "animation pointers"];
                continue;
            } else
                fail("unknown target path '" + path + "' (translation, rotation, scale or weights)");
            // glTF allows a target without a node for extensions sombra does not read.
            if (channel.target_node < 0) {
                ++skipped["animation channels without a node"];
                continue;
            }
            if (std::size_t(channel.target_node) >= count)
                fail("targets node " + std::to_string(channel.target_node) + ", but the file has " +
                     std::to_string(count) + " nodes");
            if (out->nodes[std::size_t(channel.target_node)].has_matrix)
                fail("node " + std::to_string(channel.target_node) +
                     " has a matrix: an animated node must give translation, rotation and scale");
            const bool rotation = kind == GltfChannel::Path::Rotation;
            const auto [it, is_new] =
                read.try_emplace({channel.sampler, rotation}, std::uint32_t(out->samplers.size()));
            if (is_new) {
                out->samplers.push_back(read_sampler(r, animation, channel.sampler, rotation,
                                                     name + ": sampler " + std::to_string(channel.sampler), budget));
                out->end_time = std::max(out->end_time, double(out->samplers.back().times.back()));
            }
            out->channels.push_back({std::uint32_t(channel.target_node), kind, it->second});
        }
    }
    if (out->channels.empty()) return nullptr;
    return out;
}

Motion motion_of(const GltfNodeAnimation* animation, std::size_t node_count) {
    Motion out{std::vector<char>(node_count, 0), {}};
    if (!animation) return out;
    for (const GltfChannel& c : animation->channels) out.moving[c.node] = 1;
    for (const std::uint32_t n : animation->order)  // parents first
        if (const int parent = animation->nodes[n].parent; parent >= 0 && out.moving[std::size_t(parent)])
            out.moving[n] = 1;
    out.at_start = gltf_node_worlds(*animation, 0.0);
    return out;
}

}  // namespace sombra::gltf
