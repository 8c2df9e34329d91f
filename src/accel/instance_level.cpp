// The tree over instances: a binned SAH build on the instances' world boxes
// with one instance a leaf (each costs a whole traversal of its mesh's
// structure, so leaves are not worth sharing), traversed nearest child
// first with a slab test.
#include "accel/instance_level.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "accel/bvh_build_refs.h"

namespace sombra {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kBins = 16;
// The deepest tree the build makes: SAH splits to this depth, median splits
// below, which halve the count (2^23 instances at most: kMaxInstances).
constexpr int kMaxSahDepth = 40;
constexpr int kStackSize = 128;

// The BVH build's box (bvh_build_refs.h); its centre, for binning.
using bvh_build::Box;
Vec3 center(const Box& b) { return 0.5f * (b.bmin + b.bmax); }

// The world box of `mesh` placed by `to_world`: its own box's eight corners
// carried over (an affine map keeps the mesh inside them).
Box world_box(const Box& object_box, const Transform& to_world) {
    Box box;
    if (!(object_box.bmin.x <= object_box.bmax.x)) return box;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 c{corner & 1 ? object_box.bmax.x : object_box.bmin.x,
                     corner & 2 ? object_box.bmax.y : object_box.bmin.y,
                     corner & 4 ? object_box.bmax.z : object_box.bmin.z};
        box.grow(transform_point(to_world, c));
    }
    return box;
}

Box mesh_box(const TriangleMesh& mesh) {
    Box box;
    for (const Index3& t : mesh.triangles)
        for (const std::uint32_t v : t)
            if (v < mesh.positions.size() && is_finite(mesh.positions[v])) box.grow(mesh.positions[v]);
    return box;
}

struct TreeBuilder {
    const std::vector<Box>& boxes;
    std::vector<std::uint32_t>& order;  // instance indices, partitioned in place
    std::vector<InstanceNode>& nodes;

    void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth) {
        Box bounds, centers;
        for (std::uint32_t i = begin; i < end; ++i) {
            bounds.grow(boxes[order[i]]);
            centers.grow(center(boxes[order[i]]));
        }
        nodes[node].bmin = bounds.bmin;
        nodes[node].bmax = bounds.bmax;
        if (end - begin == 1) {
            nodes[node].left_or_instance = order[begin];
            nodes[node].is_leaf = 1;
            return;
        }
        const std::uint32_t mid = split(begin, end, centers, depth);
        const auto left = static_cast<std::uint32_t>(nodes.size());
        nodes.resize(nodes.size() + 2);
        nodes[node].left_or_instance = left;
        build(left, begin, mid, depth + 1);
        build(left + 1, mid, end, depth + 1);
    }

    // Reorders order[begin, end) into two non-empty halves and returns where
    // the right one starts: the cheapest binned SAH plane, or the median
    // along the widest axis when no plane separates the centres (or deep).
    std::uint32_t split(std::uint32_t begin, std::uint32_t end, const Box& centers, int depth) {
        const Vec3 extent = centers.bmax - centers.bmin;
        int best_axis = -1, best_bin = 0;
        float best_cost = kInf;
        for (int axis = 0; axis < 3 && depth < kMaxSahDepth; ++axis) {
            if (!(extent[axis] > 0.0f)) continue;
            std::array<Box, kBins> bin_box;
            std::array<std::uint32_t, kBins> bin_count{};
            for (std::uint32_t i = begin; i < end; ++i) {
                const int b = bin_of(center(boxes[order[i]]), centers, axis);
                bin_box[b].grow(boxes[order[i]]);
                ++bin_count[b];
            }
            // Sweep from the right, then from the left: cost of each plane.
            std::array<float, kBins> right_cost{};
            Box acc;
            std::uint32_t count = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.grow(bin_box[b]);
                count += bin_count[b];
                right_cost[b] = acc.half_area() * static_cast<float>(count);
            }
            acc = Box{};
            count = 0;
            for (int b = 1; b < kBins; ++b) {
                acc.grow(bin_box[b - 1]);
                count += bin_count[b - 1];
                const float cost = acc.half_area() * static_cast<float>(count) + right_cost[b];
                if (count > 0 && count < end - begin && cost < best_cost) {
                    best_cost = cost;
                    best_axis = axis;
                    best_bin = b;
                }
            }
        }
        if (best_axis >= 0) {
            const auto it = std::partition(order.begin() + begin, order.begin() + end, [&](std::uint32_t i) {
                return bin_of(center(boxes[i]), centers, best_axis) < best_bin;
            });
            return static_cast<std::uint32_t>(it - order.begin());
        }
        const int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
        const std::uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                         [&](std::uint32_t a, std::uint32_t b) {
                             const float ca = center(boxes[a])[axis], cb = center(boxes[b])[axis];
                             return ca < cb || (ca == cb && a < b);
                         });
        return mid;
    }

    static int bin_of(Vec3 center, const Box& centers, int axis) {
        const float f = (center[axis] - centers.bmin[axis]) / (centers.bmax[axis] - centers.bmin[axis]);
        return std::clamp(static_cast<int>(f * kBins), 0, kBins - 1);
    }
};

// The world ray in instance `instance`'s coordinates: the same parameter t
// reaches the same point (the direction is carried, not normalised).
Ray to_object(const Instance& instance, const Ray& ray) {
    return Ray{transform_point(instance.world_to_object, ray.origin),
               transform_vector(instance.world_to_object, ray.dir), ray.tmax};
}

// Entry and exit of the ray's slab test against a node's box, widened by a
// few ulps so that rounding never drops a box the ray touches; NaN slabs
// (a zero direction component on the box's plane) leave the range as it is.
bool enter_box(const InstanceNode& node, Vec3 origin, Vec3 inv_dir, float tmax, float& tnear) {
    float t0 = 0.0f, t1 = tmax;
    for (int a = 0; a < 3; ++a) {
        float lo = (node.bmin[a] - origin[a]) * inv_dir[a];
        float hi = (node.bmax[a] - origin[a]) * inv_dir[a];
        if (lo > hi) std::swap(lo, hi);
        if (lo > t0) t0 = lo;
        if (hi * (1.0f + 0x1p-20f) < t1) t1 = hi * (1.0f + 0x1p-20f);
    }
    tnear = t0;
    return t0 <= t1;
}

// Visits the instances whose boxes the ray enters, nearest first;
// `visit(instance, tmax)` returns the new tmax (and true to stop).
template <class Visit>
void visit_instances(const InstanceLevel& level, const Ray& ray, Visit visit) {
    const Vec3 inv{1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z};
    float tmax = ray.tmax;
    struct Entry {
        std::uint32_t node;
        float tnear;
    };
    std::array<Entry, kStackSize> stack;
    int size = 0;
    float tnear = 0;
    if (!enter_box(level.nodes[0], ray.origin, inv, tmax, tnear)) return;
    stack[size++] = {0, tnear};
    while (size > 0) {
        const Entry entry = stack[--size];
        if (entry.tnear >= tmax) continue;
        const InstanceNode& node = level.nodes[entry.node];
        if (node.is_leaf) {
            if (visit(node.left_or_instance, tmax)) return;
            continue;
        }
        const std::uint32_t left = node.left_or_instance;
        float t_left = 0, t_right = 0;
        const bool in_left = enter_box(level.nodes[left], ray.origin, inv, tmax, t_left);
        const bool in_right = enter_box(level.nodes[left + 1], ray.origin, inv, tmax, t_right);
        // The farther child goes on the stack first: the nearer is popped next.
        if (in_left && in_right) {
            const bool left_first = t_left <= t_right;
            stack[size++] = left_first ? Entry{left + 1, t_right} : Entry{left, t_left};
            stack[size++] = left_first ? Entry{left, t_left} : Entry{left + 1, t_right};
        } else if (in_left) {
            stack[size++] = {left, t_left};
        } else if (in_right) {
            stack[size++] = {left + 1, t_right};
        }
    }
}

}  // namespace

namespace {

// The tree over `scene`'s instances, into level.nodes.
void build_tree(InstanceLevel& level, const Scene& scene) {
    std::vector<Box> object_boxes(scene.instanced_meshes.size());
    for (std::size_t m = 0; m < object_boxes.size(); ++m) object_boxes[m] = mesh_box(scene.instanced_meshes[m]);
    std::vector<Box> boxes(scene.instances.size());
    tbb::parallel_for(std::size_t{0}, boxes.size(), [&](std::size_t i) {
        const Instance& instance = scene.instances[i];
        boxes[i] = world_box(object_boxes[instance.mesh], instance.object_to_world);
    });
    // Instances that can never be hit (an empty mesh) stay out of the tree.
    std::vector<std::uint32_t> order;
    order.reserve(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (boxes[i].bmin.x <= boxes[i].bmax.x) order.push_back(static_cast<std::uint32_t>(i));
    if (order.empty()) return;
    level.nodes.reserve(2 * order.size() - 1);
    level.nodes.resize(1);
    TreeBuilder{boxes, order, level.nodes}.build(0, 0, static_cast<std::uint32_t>(order.size()), 0);
}

}  // namespace

std::shared_ptr<const InstanceLevel> make_instance_level(const Scene& scene, AccelKind kind) {
    if (scene.instances.empty()) return nullptr;
    auto level = std::make_shared<InstanceLevel>();
    level->kind = kind;
    level->instances = &scene.instances;
    auto meshes = std::make_shared<std::vector<Accel>>(scene.instanced_meshes.size());
    // Meshes build in parallel; each BVH build is itself parallel inside.
    tbb::parallel_for(std::size_t{0}, scene.instanced_meshes.size(), [&](std::size_t m) {
        const TriangleMesh& mesh = scene.instanced_meshes[m];
        (*meshes)[m] = make_accel(mesh, kind, make_cutouts(mesh, scene.materials, scene.textures));
    });
    level->meshes = std::move(meshes);
    if (kind != AccelKind::Brute) build_tree(*level, scene);
    return level;
}

std::shared_ptr<const InstanceLevel> replace_instance_tree(const InstanceLevel& previous, const Scene& scene) {
    auto level = std::make_shared<InstanceLevel>();
    level->kind = previous.kind;
    level->instances = &scene.instances;
    level->meshes = previous.meshes;
    if (level->kind != AccelKind::Brute) build_tree(*level, scene);
    return level;
}

bool intersect_instances(const InstanceLevel& level, const Ray& ray, Hit& hit) {
    const std::vector<Instance>& instances = *level.instances;
    bool found = false;
    const auto try_instance = [&](std::uint32_t i, float tmax) {
        Ray local = to_object(instances[i], ray);
        local.tmax = tmax;
        Hit h;
        if (!intersect((*level.meshes)[instances[i].mesh], local, h)) return false;
        h.instance = i;
        hit = h;
        found = true;
        return true;
    };
    if (level.kind == AccelKind::Brute) {
        float tmax = ray.tmax;
        for (std::uint32_t i = 0; i < instances.size(); ++i)
            if (try_instance(i, tmax)) tmax = hit.t;
        return found;
    }
    if (level.nodes.empty()) return false;
    // The visitor narrows tmax by hand: visit_instances reads it back.
    float best = ray.tmax;
    visit_instances(level, ray, [&](std::uint32_t i, float& tmax) {
        if (try_instance(i, best)) best = hit.t;
        tmax = best;
        return false;
    });
    return found;
}

bool occluded_instances(const InstanceLevel& level, const Ray& ray) {
    const std::vector<Instance>& instances = *level.instances;
    const auto blocks = [&](std::uint32_t i) {
        return occluded((*level.meshes)[instances[i].mesh], to_object(instances[i], ray));
    };
    if (level.kind == AccelKind::Brute) {
        for (std::uint32_t i = 0; i < instances.size(); ++i)
            if (blocks(i)) return true;
        return false;
    }
    if (level.nodes.empty()) return false;
    bool hit = false;
    visit_instances(level, ray, [&](std::uint32_t i, float&) { return hit = blocks(i); });
    return hit;
}

std::size_t instance_level_memory_bytes(const InstanceLevel& level) {
    std::size_t bytes = level.nodes.size() * sizeof(InstanceNode);
    for (const Accel& mesh : *level.meshes) bytes += accel_memory_bytes(mesh);
    return bytes;
}

}  // namespace sombra
