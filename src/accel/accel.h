// Ray queries against the scene's triangles: the only thing the integrator
// asks of geometry. One Accel is built per render; queries are read-only and
// safe from any number of threads.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "accel/bvh.h"
#include "core/ray.h"
#include "scene/cutout.h"
#include "scene/mesh.h"
#include "scene/scene.h"

namespace sombra {

inline constexpr std::uint32_t kNoHit = 0xffffffffu;

// The closest intersection found so far. (b1, b2) are the barycentric weights
// of the triangle's second and third corner; the first has 1 - b1 - b2.
struct Hit {
    float t = 0;
    float b1 = 0, b2 = 0;
    std::uint32_t triangle = kNoHit;  // index into TriangleMesh::triangles of surface_mesh(scene, instance)
    // The instance hit (index into Scene::instances), or kNoInstance for the
    // world geometry. In an instance, t is the world ray's parameter as
    // everywhere, while b1, b2 and the corners are the mesh's own.
    std::uint32_t instance = kNoInstance;
    // The triangle's corners, triangle_corners(mesh, triangle), when the
    // backend has them at hand: the BVH copies them from the leaf it has just
    // tested, which saves shading four reads at random places in the mesh
    // (the triangle's indices and three positions). The other backends leave
    // has_corners false.
    std::array<Vec3, 3> corners{};
    bool has_corners = false;
};

enum class AccelKind {
    Brute,  // every triangle for every ray: the assignment's loop, kept as the reference
    Bvh,    // sombra's own SAH bounding volume hierarchy (the default)
#ifdef SOMBRA_HAVE_EMBREE
    Embree,  // Intel Embree 3: the yardstick for the BVH's speed (accel/embree_backend.h)
#endif
};

// "brute", "bvh" or (when built with Embree) "embree"; nullopt for a name
// this build does not offer.
std::optional<AccelKind> parse_accel_kind(std::string_view name);
std::string_view accel_name(AccelKind kind);
// Names accepted by parse_accel_kind, in the order to list them to users.
std::vector<std::string_view> available_accels();

struct EmbreeScene;    // accel/embree_backend.h
struct EmbreeApi;      // accel/embree_plugin.h
struct InstanceLevel;  // accel/instance_level.h

struct Accel {
    AccelKind kind = AccelKind::Bvh;
    const TriangleMesh* mesh = nullptr;  // not owned; must outlive the Accel
    Bvh bvh;                             // empty unless kind == Bvh
    // Surfaces with alpha cut-outs (scene/cutout.h): when active, every
    // backend drops candidate hits where the surface does not exist.
    Cutouts cutouts;
#ifdef SOMBRA_HAVE_EMBREE
    std::shared_ptr<const EmbreeScene> embree;  // null unless kind == Embree
    const EmbreeApi* embree_api = nullptr;      // the plugin's calls on it (accel/embree_plugin.h)
#endif
    // The scene's instances (spec §23): one structure per instanced mesh and
    // a tree over the instances' world bounds; null when there are none.
    std::shared_ptr<const InstanceLevel> instances;
};

// Builds the structure for `mesh` (world space). The mesh must stay alive and
// unchanged while the Accel is used. Brute builds nothing; Bvh builds in
// parallel (TBB) and deterministically: the same tree for any thread count.
// Embree builds its own BVH in its plugin (and may throw Error("embree",
// ...), or Error("--accel", ...) when the plugin is missing). With
// active `cutouts` (over the same mesh, outliving the Accel), queries ignore
// the cut-out parts of surfaces as if they were not there.
Accel make_accel(const TriangleMesh& mesh, AccelKind kind, Cutouts cutouts = {});

// The structure for a loaded scene: its world geometry with its materials'
// cut-outs, and its instances: one structure of `kind` per instanced mesh
// (built in parallel), under a tree over the instances; for Embree, Embree's
// own instancing instead (Accel::instances stays null). The scene must
// outlive the Accel.
Accel make_accel(const Scene& scene, AccelKind kind);

// `accel` (made by make_accel(scene, kind)) for the scene's instances as
// they are placed now, after set_scene_time (scene/animation.h) moved them:
// the meshes' structures are kept and only the tree over the instances is
// built again (Embree: the whole structure). Gives exactly the Accel that
// make_accel(scene, kind) would.
void update_instances(Accel& accel, const Scene& scene);

// Closest hit with 0 < t < ray.tmax (tmax itself excluded). Returns false and
// leaves `hit` untouched when nothing is hit. Between hits at exactly the same
// t the lower triangle index wins, so every backend returns the same hit
// whatever its order: the BVH's hits are bit-identical to the brute-force
// loop's (same triangle, t, b1, b2). Embree is the exception: its hits agree
// only to float rounding, it may pick either triangle of a tie, and it is
// not watertight (see accel/embree_backend.h); the rest of this paragraph is
// about sombra's own backends. Both faces of a triangle count; points on
// an edge or corner count as inside, and the test is watertight: a ray never
// slips between triangles that share an edge or corner (accel/triangle.h),
// so a ray from inside a closed mesh always hits it. Triangles that can never
// be hit: degenerate ones (see prepare_triangle in accel/triangle.h), ones
// with a non-finite corner or an out-of-range index, and the cut-out parts of
// surfaces (Accel::cutouts): a hit there is skipped and the ray goes on. Rays with a non-finite
// origin or direction, or a zero direction, hit nothing.
//
// Through instances (spec §23), the world ray is carried into each
// instance's coordinates and the same test runs there: hits within an
// instance are as bit-identical across sombra's backends as those of the
// world geometry. A world triangle wins a tie at equal t against an
// instance; between instances at equal t (coincident copies) the winner
// may differ between backends.
//
// A hit triangle always has a usable geometric normal:
// normalize(cross(p1 - p0, p2 - p0)) is a unit vector, never NaN.
bool intersect(const Accel& accel, const Ray& ray, Hit& hit);

// True when anything is hit with 0 < t < ray.tmax (shadow rays: any hit ends
// it). Agrees with intersect(): true exactly when intersect() would hit.
bool occluded(const Accel& accel, const Ray& ray);

// Bytes held by the acceleration structure itself, not counting the mesh:
// nodes plus index and precomputed triangle arrays; 0 for Brute. For Embree,
// what Embree allocated plus the buffers sombra shares with it.
std::size_t accel_memory_bytes(const Accel& accel);

}  // namespace sombra
