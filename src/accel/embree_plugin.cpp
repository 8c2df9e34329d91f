// libsombra_embree.so: accel/embree_backend.h's functions as the table of
// embree_plugin.h.
#include "accel/embree_plugin.h"

#include "accel/embree_backend.h"

namespace sombra {
namespace {

// make_embree_scene is overloaded: one name for each form.
std::shared_ptr<const EmbreeScene> mesh_scene(const TriangleMesh& mesh, const Cutouts& cutouts, bool high_quality,
                                              bool robust) {
    return make_embree_scene(mesh, cutouts, high_quality, robust);
}

std::shared_ptr<const EmbreeScene> scene_scene(const Scene& scene, const Cutouts& world_cutouts, bool high_quality,
                                               bool robust) {
    return make_embree_scene(scene, world_cutouts, high_quality, robust);
}

const EmbreeApi kApi{kEmbreeApiAbi, mesh_scene, scene_scene, intersect_embree, occluded_embree, embree_memory_bytes};

}  // namespace
}  // namespace sombra

extern "C" __attribute__((visibility("default"))) const sombra::EmbreeApi* sombra_embree_api() { return &sombra::kApi; }
