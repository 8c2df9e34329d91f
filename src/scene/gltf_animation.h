// A glTF file's node animations (spec §22, glTF 2.0 §3.11) as plain data:
// the node tree, each node's rest TRS, and the channels that replace a
// node's translation, rotation or scale with a sampled curve. The glTF
// loader fills it (io/gltf/gltf_animation.cpp); set_scene_time evaluates it.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/transform.h"

namespace sombra {

struct GltfSampler {
    enum class Interpolation { Linear, Step, CubicSpline };
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;  // finite, strictly increasing, at least one
    // `components` floats per key (3, or 4 for a rotation); CUBICSPLINE
    // keys are in-tangent, value, out-tangent triples.
    std::vector<float> values;
    int components = 3;
};

struct GltfChannel {
    enum class Path { Translation, Rotation, Scale };
    std::uint32_t node = 0;
    Path path = Path::Translation;
    std::uint32_t sampler = 0;  // index into GltfNodeAnimation::samplers
};

struct GltfNodeAnimation {
    struct Node {
        int parent = -1;
        // A node with a matrix is never animated (glTF forbids it): `matrix`
        // then holds its local transform and the TRS below are unused.
        bool has_matrix = false;
        Transform matrix;
        double translation[3] = {0, 0, 0};
        double rotation[4] = {0, 0, 0, 1};  // x, y, z, w
        double scale[3] = {1, 1, 1};
    };
    std::vector<Node> nodes;           // the file's nodes, by index
    std::vector<std::uint32_t> order;  // the nodes the scene reaches, parents first
    std::vector<GltfSampler> samplers;
    std::vector<GltfChannel> channels;  // of every animation of the file
    double end_time = 0;                // the last key time of any sampler
};

// Every node's transform to the file's world at `time` seconds (nodes the
// scene does not reach: identity). Channels replace their node's rest
// value; before the first and after the last key the end value holds.
std::vector<Transform> gltf_node_worlds(const GltfNodeAnimation& animation, double time);

// Where a camera that a glTF node carries stands and looks (glTF 2.0
// §3.10): at the node's origin, along its −z, with its +y made
// perpendicular to that for up (forward and up unit). False when the node
// has no frame there (scaled to nothing along an axis, or not finite). The
// loader and set_scene_time both place cameras so, so that time 0 gives
// the same camera bit for bit.
bool gltf_camera_frame(const Transform& world, Vec3& origin, Vec3& forward, Vec3& up);

// One sampler's value at `time` into out[0 .. components): LINEAR rotations
// by slerp on the shorter arc, rotations normalised.
void sample_gltf(const GltfSampler& sampler, bool rotation, double time, double* out);

}  // namespace sombra
