// The top level of a two-level structure (spec §23): instanced meshes keep
// one structure each, in their own coordinates, and a binary tree over the
// instances' world bounds finds the instances a ray may meet; the ray is
// carried into each one's coordinates and asks its mesh's structure.
// Internal to src/accel: the rest of sombra calls intersect()/occluded().
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "accel/accel.h"
#include "core/ray.h"
#include "core/vec3.h"
#include "scene/scene.h"

namespace sombra {

// A node of the tree over instances: children in adjacent slots; a leaf
// holds one instance.
struct InstanceNode {
    Vec3 bmin;
    std::uint32_t left_or_instance = 0;  // inner: the left child's index (right = left + 1); leaf: the instance
    Vec3 bmax;
    std::uint32_t is_leaf = 0;
};

struct InstanceLevel {
    AccelKind kind = AccelKind::Bvh;
    std::shared_ptr<const std::vector<Accel>>
        meshes;  // one per Scene::instanced_meshes, over the mesh in its coordinates
    const std::vector<Instance>* instances = nullptr;  // Scene::instances; not owned
    std::vector<InstanceNode> nodes;  // nodes[0] is the root; empty for Brute (every instance, in order)
};

// The level for `scene`'s instances, or null when it has none.
std::shared_ptr<const InstanceLevel> make_instance_level(const Scene& scene, AccelKind kind);

// The level for `scene`'s instances as they are placed now, keeping the
// meshes' structures of `previous` (made for the same scene's meshes):
// what a new moment of an animation needs (spec §22).
std::shared_ptr<const InstanceLevel> replace_instance_tree(const InstanceLevel& previous, const Scene& scene);

// intersect() and occluded() over the instances only: `hit` is replaced only
// by a hit closer than ray.tmax.
bool intersect_instances(const InstanceLevel& level, const Ray& ray, Hit& hit);
bool occluded_instances(const InstanceLevel& level, const Ray& ray);

// Bytes of the meshes' structures and the tree.
std::size_t instance_level_memory_bytes(const InstanceLevel& level);

}  // namespace sombra
