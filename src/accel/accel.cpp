// Backend selection and the brute-force reference loop.
#include "accel/accel.h"

#include <cassert>

#include "accel/embree_plugin.h"
#include "accel/instance_level.h"
#include "accel/triangle.h"

namespace sombra {
namespace {

// A candidate hit counts unless it lies on a cut-out part of a surface.
bool kept(const Cutouts& cutouts, std::size_t triangle, float b1, float b2) {
    return !cutouts.active() || surface_exists(cutouts, static_cast<std::uint32_t>(triangle), b1, b2);
}

bool intersect_brute(const TriangleMesh& mesh, const Cutouts& cutouts, const Ray& ray, Hit& hit) {
    Hit best;
    best.t = ray.tmax;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        float t, b1, b2;
        // Passing the closest t so far as tmax keeps the first (lowest
        // index) of several hits at exactly the same t.
        if (intersect_triangle(ray.origin, ray.dir, prepare_triangle(mesh, mesh.triangles[i]), best.t, t, b1, b2) &&
            kept(cutouts, i, b1, b2)) {
            best = Hit{t, b1, b2, static_cast<std::uint32_t>(i)};
        }
    }
    if (best.triangle == kNoHit) return false;
    hit = best;
    return true;
}

bool occluded_brute(const TriangleMesh& mesh, const Cutouts& cutouts, const Ray& ray) {
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        float t, b1, b2;
        if (intersect_triangle(ray.origin, ray.dir, prepare_triangle(mesh, mesh.triangles[i]), ray.tmax, t, b1, b2) &&
            kept(cutouts, i, b1, b2))
            return true;
    }
    return false;
}

}  // namespace

std::optional<AccelKind> parse_accel_kind(std::string_view name) {
    if (name == "bvh") return AccelKind::Bvh;
    if (name == "brute") return AccelKind::Brute;
#ifdef SOMBRA_HAVE_EMBREE
    if (name == "embree") return AccelKind::Embree;
#endif
    return std::nullopt;
}

std::string_view accel_name(AccelKind kind) {
    switch (kind) {
        case AccelKind::Brute: return "brute";
        case AccelKind::Bvh: return "bvh";
#ifdef SOMBRA_HAVE_EMBREE
        case AccelKind::Embree: return "embree";
#endif
    }
    return "unknown";
}

std::vector<std::string_view> available_accels() {
#ifdef SOMBRA_HAVE_EMBREE
    return {"bvh", "brute", "embree"};
#else
    return {"bvh", "brute"};
#endif
}

Accel make_accel(const TriangleMesh& mesh, AccelKind kind, Cutouts cutouts) {
    Accel accel;
    accel.kind = kind;
    accel.mesh = &mesh;
    assert(!cutouts.active() || cutouts.mesh == &mesh);
    accel.cutouts = cutouts;
    if (kind == AccelKind::Bvh) accel.bvh = make_bvh(mesh);
#ifdef SOMBRA_HAVE_EMBREE
    if (kind == AccelKind::Embree) {
        accel.embree_api = &embree_plugin();
        accel.embree = accel.embree_api->make_mesh_scene(mesh, accel.cutouts, false, false);
    }
#endif
    return accel;
}

Accel make_accel(const Scene& scene, AccelKind kind) {
#ifdef SOMBRA_HAVE_EMBREE
    // The yardstick instances with Embree's own two levels, not sombra's
    // tree over instances (accel/embree_backend.h).
    if (kind == AccelKind::Embree) {
        Accel accel;
        accel.kind = kind;
        accel.mesh = &scene.geometry;
        accel.cutouts = make_cutouts(scene.geometry, scene.materials, scene.textures);
        accel.embree_api = &embree_plugin();
        accel.embree = accel.embree_api->make_scene(scene, accel.cutouts, false, false);
        return accel;
    }
#endif
    Accel accel = make_accel(scene.geometry, kind, make_cutouts(scene.geometry, scene.materials, scene.textures));
    accel.instances = make_instance_level(scene, kind);
    return accel;
}

void update_instances(Accel& accel, const Scene& scene) {
#ifdef SOMBRA_HAVE_EMBREE
    if (accel.kind == AccelKind::Embree) {
        accel = make_accel(scene, accel.kind);
        return;
    }
#endif
    if (accel.instances != nullptr) accel.instances = replace_instance_tree(*accel.instances, scene);
}

namespace {

// The backends other than the BVH. Kept out of line: inlined into
// intersect() and occluded(), the brute-force loop makes GCC save six
// registers on entry to every call, the BVH's included.
[[gnu::noinline]] bool intersect_other(const Accel& accel, const Ray& ray, Hit& hit) {
    if (!is_traceable(ray)) return false;
#ifdef SOMBRA_HAVE_EMBREE
    if (accel.kind == AccelKind::Embree)
        return accel.embree != nullptr && accel.embree_api->intersect(*accel.embree, ray, hit);
#endif
    return intersect_brute(*accel.mesh, accel.cutouts, ray, hit);
}

[[gnu::noinline]] bool occluded_other(const Accel& accel, const Ray& ray) {
    if (!is_traceable(ray)) return false;
#ifdef SOMBRA_HAVE_EMBREE
    if (accel.kind == AccelKind::Embree)
        return accel.embree != nullptr && accel.embree_api->occluded(*accel.embree, ray);
#endif
    return occluded_brute(*accel.mesh, accel.cutouts, ray);
}

}  // namespace

namespace {

// The world geometry's part of intersect() and occluded().
bool intersect_world(const Accel& accel, const Ray& ray, Hit& hit) {
    // intersect_bvh and occluded_bvh check the ray themselves (is_traceable).
    if (accel.kind == AccelKind::Bvh)
        return accel.cutouts.active() ? intersect_bvh(accel.bvh, accel.cutouts, ray, hit)
                                      : intersect_bvh(accel.bvh, ray, hit);
    return intersect_other(accel, ray, hit);
}

bool occluded_world(const Accel& accel, const Ray& ray) {
    if (accel.kind == AccelKind::Bvh)
        return accel.cutouts.active() ? occluded_bvh(accel.bvh, accel.cutouts, ray) : occluded_bvh(accel.bvh, ray);
    return occluded_other(accel, ray);
}

// The instances' part, out of line: scenes without instances pay one test.
[[gnu::noinline]] bool intersect_with_instances(const Accel& accel, const Ray& ray, Hit& hit) {
    if (!is_traceable(ray)) return false;
    Ray rest = ray;
    const bool world = intersect_world(accel, ray, hit);
    if (world) rest.tmax = hit.t;
    return intersect_instances(*accel.instances, rest, hit) || world;
}

[[gnu::noinline]] bool occluded_with_instances(const Accel& accel, const Ray& ray) {
    if (!is_traceable(ray)) return false;
    return occluded_world(accel, ray) || occluded_instances(*accel.instances, ray);
}

}  // namespace

bool intersect(const Accel& accel, const Ray& ray, Hit& hit) {
    if (accel.mesh == nullptr) return false;
    if (accel.instances != nullptr) return intersect_with_instances(accel, ray, hit);
    return intersect_world(accel, ray, hit);
}

bool occluded(const Accel& accel, const Ray& ray) {
    if (accel.mesh == nullptr) return false;
    if (accel.instances != nullptr) return occluded_with_instances(accel, ray);
    return occluded_world(accel, ray);
}

std::size_t accel_memory_bytes(const Accel& accel) {
    const std::size_t instances = accel.instances != nullptr ? instance_level_memory_bytes(*accel.instances) : 0;
#ifdef SOMBRA_HAVE_EMBREE
    if (accel.kind == AccelKind::Embree)
        return instances + (accel.embree != nullptr ? accel.embree_api->memory_bytes(*accel.embree) : 0);
#endif
    return instances + (accel.kind == AccelKind::Bvh ? bvh_memory_bytes(accel.bvh) : 0);
}

}  // namespace sombra
