// The Embree yardstick (`--accel embree`, accel/embree_backend.h) in a
// plugin of its own, libsombra_embree.so (embree_plugin.cpp), so that the
// executable and the Python module link no Embree and the .deb's sombra
// does not need it (the sombra-embree package adds it). Plugin and
// executable are built together from one tree: the table passes sombra's
// own types, and its `abi` refuses a plugin of another build.
#pragma once

#include <cstddef>
#include <memory>

#include "core/ray.h"
#include "scene/cutout.h"
#include "scene/mesh.h"

namespace sombra {

struct EmbreeScene;
struct Hit;
struct Scene;

struct EmbreeApi {
    int abi;  // kEmbreeApiAbi
    // make_embree_scene's two forms (accel/embree_backend.h).
    std::shared_ptr<const EmbreeScene> (*make_mesh_scene)(const TriangleMesh& mesh, const Cutouts& cutouts,
                                                          bool high_quality, bool robust);
    std::shared_ptr<const EmbreeScene> (*make_scene)(const Scene& scene, const Cutouts& world_cutouts,
                                                     bool high_quality, bool robust);
    bool (*intersect)(const EmbreeScene& scene, const Ray& ray, Hit& hit);
    bool (*occluded)(const EmbreeScene& scene, const Ray& ray);
    std::size_t (*memory_bytes)(const EmbreeScene& scene);
};

inline constexpr int kEmbreeApiAbi = 1;
inline constexpr const char* kEmbreeEntry = "sombra_embree_api";
using EmbreeApiEntry = const EmbreeApi* (*)();

// The plugin's table; throws Error("--accel", ...) saying why when this
// sombra has none (not built with Embree, or the plugin is not installed).
const EmbreeApi& embree_plugin();

}  // namespace sombra

// The plugin's one exported function (embree_plugin.cpp).
extern "C" const sombra::EmbreeApi* sombra_embree_api();
