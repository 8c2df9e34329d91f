// sombra's own bounding volume hierarchy: a binary SAH tree in one flat array
// of 32-byte nodes.
#pragma once

#include <cstdint>
#include <vector>

#include "core/ray.h"
#include "core/vec3.h"
#include "scene/mesh.h"

namespace sombra {

struct Hit;

struct BvhNode {
    Vec3 bmin;
    std::uint32_t left_or_first;  // inner node: index of the left child (right = left + 1); leaf: first entry in Bvh::triangle_order
    Vec3 bmax;
    std::uint32_t count;          // 0 for an inner node, else the leaf's triangle count
};
static_assert(sizeof(BvhNode) == 32);

struct Bvh {
    std::vector<BvhNode> nodes;               // nodes[0] is the root; empty for an empty mesh
    std::vector<std::uint32_t> triangle_order;  // leaf entries, indices into TriangleMesh::triangles
};

Bvh make_bvh(const TriangleMesh& mesh);
bool intersect_bvh(const Bvh& bvh, const TriangleMesh& mesh, const Ray& ray, Hit& hit);
bool occluded_bvh(const Bvh& bvh, const TriangleMesh& mesh, const Ray& ray);

}  // namespace sombra
