// A light tree over the emissive triangles (Conty Estevez & Kulla 2018,
// "Importance Sampling of Many Lights with Adaptive Tree Splitting", without
// the splitting; as pbrt-v4's BVHLightSampler): a binary tree whose nodes
// bound their emitters' positions (a box), emission directions (a cone) and
// total power. One emitter is chosen for a shading point x by descending
// from the root, picking each child in proportion to an importance that
// bounds what the child's emitters can send to x from above (power · cosine
// bounds / distance²); the product of the choices is the emitter's
// probability. The environment is not in the tree (render/lights/lights.h chooses
// between the two).
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace sombra {

// One node, 48 bytes, in a depth-first flat array: an interior node's first
// child is the next node, its second child is at `payload`'s index. A leaf
// holds exactly one emitter, whose index (into LightSet::emitters) is in
// `payload`.
struct LightTreeNode {
    Vec3 bmin;        // bounding box of the emitters' corners
    float power = 0;  // Σ luminance(ke) · area · π · sides
    Vec3 bmax;
    float cos_theta_o = 1;      // every emitter normal lies within θ_o of ±axis (see kTwoSided)
    Vec3 axis;                  // unit axis of the normal cone
    std::uint32_t payload = 0;  // kLeaf | kTwoSided | index

    static constexpr std::uint32_t kLeaf = 1u << 31;
    // Some emitter below shines from both faces: the cone then bounds the
    // normals up to sign (both ±axis), and emission is bounded on both sides.
    static constexpr std::uint32_t kTwoSided = 1u << 30;
    static constexpr std::uint32_t kIndexMask = kTwoSided - 1;

    bool leaf() const { return (payload & kLeaf) != 0; }
    bool two_sided() const { return (payload & kTwoSided) != 0; }
    std::uint32_t index() const { return payload & kIndexMask; }
};

struct LightTree {
    std::vector<LightTreeNode> nodes;  // root first; empty without emitters
    // Per emitter, its path from the root: bit k is 1 where the k-th step
    // goes to the second child (the depth is at most 63).
    std::vector<std::uint64_t> trails;
};

// What make_light_tree needs of one emitter.
struct LightTreeEmitter {
    Vec3 p0, p1, p2;  // corners; the winding normal (p1−p0)×(p2−p0) is the front
    float power = 0;  // > 0
    bool two_sided = false;
};

// The tree over `emitters` (indices in the result refer to this array),
// built top down by Conty & Kulla's surface area orientation heuristic
// (SAOH) over 12 centroid bins per axis, down to one emitter per leaf; a
// median split where binning cannot separate the centroids.
LightTree make_light_tree(const std::vector<LightTreeEmitter>& emitters);

// The importance of `node` for a point x with unit normal n (zero: no
// normal, e.g. in a medium): power · cos θ' / d², times cos θ'_i when n is
// given, where θ' bounds from below the angle between any emitter normal
// below and the direction to x, θ'_i the angle between ±n and any point of
// the box, and d the distance from x to the box centre, clamped below by
// half the box diagonal. Conservative: 0 only when no emitter below can
// send light to x's hemisphere(s).
float light_tree_importance(const LightTreeNode& node, Vec3 x, Vec3 n);

// An emitter chosen by descending from the root with u ∈ [0, 1); its
// index into the tree's emitter array and the probability of choosing it.
struct LightTreeChoice {
    std::uint32_t emitter = 0;
    float probability = 0;  // 0: the sample failed (no emitter can light x)
};

LightTreeChoice sample_light_tree(const LightTree& tree, Vec3 x, Vec3 n, float u);

// The probability that sample_light_tree, called with the same x and n,
// returns `emitter`: the same float operations, so it equals the sampled
// probability exactly. Summed over all emitters it is at most 1: the rest is
// the probability that the descent reaches a node whose children both have
// importance 0 (a looser parent bound let it through), where the sample fails.
float pmf_light_tree(const LightTree& tree, Vec3 x, Vec3 n, std::uint32_t emitter);

}  // namespace sombra
