// The Embree 3 backend: one device per Accel, one triangle geometry for the
// world mesh and Embree's own instancing for Scene::instances (one scene per
// instanced mesh under instance geometries), queried with rtcIntersect1 /
// rtcOccluded1.
#include "accel/embree_backend.h"

#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/triangle.h"
#include "core/error.h"
#include "scene/scene.h"

namespace sombra {

// One mesh handed to Embree: sombra's copies Embree reads and the cut-outs
// its filter functions read (geometry user data: this struct).
struct EmbreeMesh {
    // x, y, z per vertex plus one float: Embree reads the last vertex with a
    // 16-byte load.
    std::vector<float> vertices;
    // Only when some triangles cannot be hit: the ones handed to Embree and
    // their indices in the mesh (Embree's primID → TriangleMesh index).
    // Both empty when every triangle is kept: Embree then reads the mesh's
    // own index array and primID is the triangle index.
    std::vector<Index3> kept_triangles;
    std::vector<std::uint32_t> mesh_index_of;
    Cutouts cutouts;
};

struct EmbreeScene {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;  // the top level: instances 0 … n − 1 by ID, then the world geometry
    // One Embree scene per instanced mesh (spec §23), which the top level's
    // instance geometries draw.
    std::vector<RTCScene> mesh_scenes;
    // Net bytes Embree has allocated on `device` (its memory monitor adds
    // allocations and subtracts frees, from any build thread).
    std::atomic<std::int64_t> embree_bytes{0};
    EmbreeMesh world;
    // Per instanced mesh; pointers, as the filter functions hold their address.
    std::vector<std::unique_ptr<EmbreeMesh>> meshes;
    // Scene::instances[i].mesh: which of `meshes` instance i (Embree's instID) draws.
    std::vector<std::uint32_t> instance_mesh;
    // The first error Embree reported (it may report from build threads).
    std::mutex error_mutex;
    std::string first_error;

    EmbreeScene() = default;
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;
    ~EmbreeScene() {
        if (scene != nullptr) rtcReleaseScene(scene);
        for (RTCScene mesh_scene : mesh_scenes)
            if (mesh_scene != nullptr) rtcReleaseScene(mesh_scene);
        if (device != nullptr) rtcReleaseDevice(device);
    }
};

namespace {

bool count_memory(void* user, ssize_t bytes, bool /*post*/) {
    static_cast<EmbreeScene*>(user)->embree_bytes.fetch_add(bytes, std::memory_order_relaxed);
    return true;  // never refuse an allocation
}

void record_error(void* user, RTCError /*code*/, const char* message) {
    auto* s = static_cast<EmbreeScene*>(user);
    const std::lock_guard lock(s->error_mutex);
    if (s->first_error.empty()) s->first_error = message != nullptr ? message : "unknown error";
}

void throw_if_failed(EmbreeScene& s, const char* doing) {
    const RTCError code = rtcGetDeviceError(s.device);
    if (code == RTC_ERROR_NONE) return;
    const std::lock_guard lock(s.error_mutex);
    throw Error("embree", std::string(doing) + " failed: " +
                              (s.first_error.empty() ? "error " + std::to_string(int(code)) : s.first_error));
}

// Embree accepts t <= tfar; sombra wants t < tmax. The float just below tmax
// makes the two agree (and turns +inf into FLT_MAX).
float embree_tfar(float tmax) { return std::nextafter(tmax, 0.0f); }

RTCRay make_rtc_ray(const Ray& ray) {
    RTCRay r;
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.tnear = 0.0f;  // Embree accepts t > tnear, as sombra wants t > 0
    r.dir_x = ray.dir.x;
    r.dir_y = ray.dir.y;
    r.dir_z = ray.dir.z;
    r.time = 0.0f;
    r.tfar = embree_tfar(ray.tmax);
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    return r;
}

// The mesh's index of Embree's primitive `prim`.
std::uint32_t mesh_triangle(const EmbreeMesh& m, std::uint32_t prim) {
    return m.mesh_index_of.empty() ? prim : m.mesh_index_of[prim];
}

// Embree's hit filter under cut-outs: a candidate hit on a cut-out part of a
// surface is marked invalid, and Embree's traversal goes on past it. Each
// mesh's geometry carries its own EmbreeMesh, so a hit inside an instance
// reads the instanced mesh's materials (instances share their mesh's).
void drop_cut_out_hits(const RTCFilterFunctionNArguments* args) {
    const auto& m = *static_cast<const EmbreeMesh*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
        clamp_barycentrics(u, v);  // as intersect_embree reports the hit
        if (!surface_exists(m.cutouts, mesh_triangle(m, RTCHitN_primID(args->hit, args->N, i)), u, v))
            args->valid[i] = 0;
    }
}

// Attaches the triangles of `mesh` that sombra can hit (the same ones
// make_bvh keeps: in-range indices, finite corners, non-zero area) to
// `target` as geometry `id`, with `m` holding the buffers Embree shares.
void attach_triangles(EmbreeScene& s, RTCScene target, unsigned id, EmbreeMesh& m, const TriangleMesh& mesh,
                      const Cutouts& cutouts, bool high_quality) {
    const std::size_t vertex_count = mesh.positions.size();
    std::vector<std::uint32_t> kept;
    kept.reserve(mesh.triangles.size());  // no doubling: the list is 4 bytes a triangle
    bool all_kept = true;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const Index3& t = mesh.triangles[i];
        const bool hittable =
            t[0] < vertex_count && t[1] < vertex_count && t[2] < vertex_count &&
            is_hittable(prepare_triangle(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]));
        if (hittable) kept.push_back(static_cast<std::uint32_t>(i));
        all_kept = all_kept && hittable;
    }
    if (!all_kept) {
        m.kept_triangles.reserve(kept.size());
        for (std::uint32_t i : kept) m.kept_triangles.push_back(mesh.triangles[i]);
        m.mesh_index_of = std::move(kept);
    }
    // When every triangle is kept the list is not needed: freed before
    // Embree's build, not held through it.
    std::vector<std::uint32_t>().swap(kept);
    const std::size_t triangle_count = all_kept ? mesh.triangles.size() : m.kept_triangles.size();
    if (triangle_count == 0) return;

    m.vertices.resize(3 * vertex_count + 1, 0.0f);
    for (std::size_t i = 0; i < vertex_count; ++i) {
        m.vertices[3 * i + 0] = mesh.positions[i].x;
        m.vertices[3 * i + 1] = mesh.positions[i].y;
        m.vertices[3 * i + 2] = mesh.positions[i].z;
    }
    const Index3* indices = all_kept ? mesh.triangles.data() : m.kept_triangles.data();
    RTCGeometry geometry = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (high_quality) rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.vertices.data(), 0,
                               3 * sizeof(float), vertex_count);
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0, sizeof(Index3),
                               triangle_count);
    if (cutouts.active()) {
        m.cutouts = cutouts;
        rtcSetGeometryUserData(geometry, &m);
        rtcSetGeometryIntersectFilterFunction(geometry, drop_cut_out_hits);
        rtcSetGeometryOccludedFilterFunction(geometry, drop_cut_out_hits);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(target, geometry, id);
    rtcReleaseGeometry(geometry);  // the scene holds it now
    throw_if_failed(s, "setting up the triangles");
}

// A new scene on the device with the build settings the caller asked for:
// by default Embree as most users run it (RTC_SCENE_FLAG_NONE, MEDIUM
// quality); HIGH is its spatial-split builder.
RTCScene new_scene(EmbreeScene& s, bool high_quality, bool robust) {
    RTCScene scene = rtcNewScene(s.device);
    throw_if_failed(s, "creating the scene");
    if (high_quality) rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    if (robust) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    return scene;
}

std::shared_ptr<EmbreeScene> new_device() {
    auto s = std::make_shared<EmbreeScene>();
    s->device = rtcNewDevice(nullptr);
    if (s->device == nullptr) {
        throw Error("embree",
                    "could not create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    }
    rtcSetDeviceErrorFunction(s->device, record_error, s.get());
    rtcSetDeviceMemoryMonitorFunction(s->device, count_memory, s.get());
    return s;
}

}  // namespace

std::shared_ptr<const EmbreeScene> make_embree_scene(const TriangleMesh& mesh, const Cutouts& cutouts,
                                                     bool high_quality, bool robust) {
    auto s = new_device();
    s->scene = new_scene(*s, high_quality, robust);
    attach_triangles(*s, s->scene, 0, s->world, mesh, cutouts, high_quality);
    rtcCommitScene(s->scene);
    throw_if_failed(*s, "building the BVH");
    return s;
}

std::shared_ptr<const EmbreeScene> make_embree_scene(const Scene& scene, const Cutouts& world_cutouts,
                                                     bool high_quality, bool robust) {
    auto s = new_device();
    // Each instanced mesh's scene is committed (Embree builds it, in
    // parallel inside) before the top level that instances it.
    s->meshes.reserve(scene.instanced_meshes.size());
    s->mesh_scenes.reserve(scene.instanced_meshes.size());
    for (const TriangleMesh& mesh : scene.instanced_meshes) {
        s->meshes.push_back(std::make_unique<EmbreeMesh>());
        s->mesh_scenes.push_back(new_scene(*s, high_quality, robust));
        attach_triangles(*s, s->mesh_scenes.back(), 0, *s->meshes.back(), mesh,
                         make_cutouts(mesh, scene.materials, scene.textures), high_quality);
        rtcCommitScene(s->mesh_scenes.back());
        throw_if_failed(*s, "building an instanced mesh's BVH");
    }
    s->scene = new_scene(*s, high_quality, robust);
    // Instance i is geometry i, so Embree's instID is the index into
    // Scene::instances; the world geometry comes after them.
    s->instance_mesh.reserve(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        s->instance_mesh.push_back(instance.mesh);
        RTCGeometry geometry = rtcNewGeometry(s->device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geometry, s->mesh_scenes[instance.mesh]);
        // Transform::m is row-major with [0 0 0 1] last: its first 12 floats
        // are the 3×4 matrix.
        rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, instance.object_to_world.m.data());
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(s->scene, geometry, static_cast<unsigned>(i));
        rtcReleaseGeometry(geometry);
    }
    throw_if_failed(*s, "setting up the instances");
    attach_triangles(*s, s->scene, static_cast<unsigned>(scene.instances.size()), s->world, scene.geometry,
                     world_cutouts, high_quality);
    rtcCommitScene(s->scene);
    throw_if_failed(*s, "building the BVH");
    return s;
}

bool intersect_embree(const EmbreeScene& s, const Ray& ray, Hit& hit) {
    if (!(ray.tmax > 0.0f)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray = make_rtc_ray(ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s.scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

    // Embree's u, v are the weights of corners 1 and 2, as sombra's b1, b2
    // (in an instance, of the mesh's own triangle, as sombra's too). Its
    // division can leave them a rounding step outside the triangle; clamp
    // as intersect_triangle does, so b0 = 1 − b1 − b2 ≥ 0. Embree carries
    // the ray into an instance without normalising its direction: tfar is
    // the world ray's parameter.
    const std::uint32_t instance = rh.hit.instID[0];
    const bool in_instance = instance != RTC_INVALID_GEOMETRY_ID;
    const EmbreeMesh& m = in_instance ? *s.meshes[s.instance_mesh[instance]] : s.world;
    float u = rh.hit.u, v = rh.hit.v;
    clamp_barycentrics(u, v);
    hit.t = rh.ray.tfar;
    hit.b1 = u;
    hit.b2 = v;
    hit.triangle = mesh_triangle(m, rh.hit.primID);
    hit.instance = in_instance ? instance : kNoInstance;
    hit.has_corners = false;
    return true;
}

bool occluded_embree(const EmbreeScene& s, const Ray& ray) {
    if (!(ray.tmax > 0.0f)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = make_rtc_ray(ray);
    rtcOccluded1(s.scene, &context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to −inf when something is hit
}

std::size_t embree_memory_bytes(const EmbreeScene& s) {
    const std::int64_t embree = s.embree_bytes.load(std::memory_order_relaxed);
    const auto copies = [](const EmbreeMesh& m) {
        return m.vertices.size() * sizeof(float) + m.kept_triangles.size() * sizeof(Index3) +
               m.mesh_index_of.size() * sizeof(std::uint32_t);
    };
    std::size_t bytes = static_cast<std::size_t>(embree > 0 ? embree : 0) + copies(s.world);
    for (const auto& m : s.meshes) bytes += copies(*m);
    return bytes + s.instance_mesh.size() * sizeof(std::uint32_t);
}

}  // namespace sombra
