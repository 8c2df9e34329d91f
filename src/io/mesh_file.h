// Mesh files → LoadedMesh: OBJ (+MTL), PLY and glTF 2.0. LoadedMesh is
// what the readers of every mesh format produce, and what the scene readers
// place in a scene.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec3.h"
#include "scene/gltf_animation.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/texture.h"
#include "scene/transform.h"

namespace sombra {

// A camera that a model file places (glTF), in the file's coordinates: at
// `origin`, looking along `forward`, with `up` (both unit, perpendicular),
// and either a pinhole's vertical field of view and the image aspect (width
// / height) the file asks for, 0 when it leaves that to the image, or
// (ymag > 0) an orthographic view's half-height (spec §24).
struct ModelCamera {
    Vec3 origin, forward, up;
    float yfov_degrees = 45;
    float aspect = 0;
    float ymag = 0;
};

// A mesh a file draws several times (glTF: a mesh several nodes use, or
// EXT_mesh_gpu_instancing; spec §23), stored once in its own coordinates.
struct InstancedPart {
    TriangleMesh mesh;  // material_ids index LoadedMesh::materials
    // Each: the mesh's coordinates → the file's (animated: at time 0); at
    // least two, or one drawn by an animated node.
    std::vector<Transform> instances;
    // Animated parts (some node animated, LoadedMesh::animation): per
    // instance, the node drawing it and what acts before the node's world
    // transform (EXT_mesh_gpu_instancing's, else the identity). Empty: static.
    std::vector<std::uint32_t> nodes{};
    std::vector<Transform> local{};
    // Who placed instances[k], for messages: the last origin with
    // first <= k; `numbered` origins (GPU instancing) also name k − first.
    struct Origin {
        std::size_t first = 0;
        std::string name;  // "node 3"
        bool numbered = false;
    };
    std::vector<Origin> origins;
};

// "node 3", or "node 3: instance 2" for instance k of `part`.
std::string instance_name(const InstancedPart& part, std::size_t k);

// A mesh file as read from disk: geometry in the file's own coordinates and
// the materials its faces refer to. Loaders always leave at least one
// material when there are triangles (the default one for faces without).
// Materials' TextureRefs index `textures`, the file's own table.
struct LoadedMesh {
    TriangleMesh mesh;
    std::vector<Material> materials;
    std::vector<Texture> textures{};
    // Meshes drawn several times, apart from `mesh` (which holds what is
    // drawn once, and may then be empty); glTF only.
    std::vector<InstancedPart> instanced{};

    // The lights and the first camera the file's scene places, in the
    // file's coordinates (glTF; none for OBJ and PLY).
    std::vector<PunctualLight> lights;
    std::optional<ModelCamera> camera;
    // The file's node animations (glTF, spec §22), which the parts with
    // `nodes` follow; none when nothing the scene places moves.
    std::shared_ptr<const GltfNodeAnimation> animation{};
    // With `animation`: per light, the animated node that carries it (-1:
    // none) and the light in that node's coordinates; the camera's node
    // when it is animated (-1: none). `lights` and `camera` are as at time 0.
    std::vector<int> light_nodes{};
    std::vector<PunctualLight> lights_in_nodes{};
    int camera_node = -1;
};

// Reads an OBJ file and the MTL files it names (spec §5, §9). Polygons are
// fan-triangulated from their first corner (concave ones ear-clipped); faces
// with fewer than 3 corners, triangles touching non-finite positions and
// out-of-range normal indices are dropped or ignored with a warning.
// Throws Error("file:line", ...) for a file that cannot be read or is invalid.
LoadedMesh load_obj(const std::filesystem::path& path, Diagnostics& diag);

// Reads an ascii or binary (little/big endian) PLY file (spec §9).
LoadedMesh load_ply(const std::filesystem::path& path, Diagnostics& diag);

// Reads a glTF 2.0 file, .gltf (JSON, external or embedded buffers) or .glb
// (spec §13): the default scene's meshes in the file's world space (node
// transforms applied; a mesh drawn more than once is an InstancedPart
// instead, spec §23), its materials as `pbr`, its point lights and first
// perspective camera. Throws Error(path, ...) for a broken file.
LoadedMesh load_gltf(const std::filesystem::path& path, Diagnostics& diag);

// Dispatches on the extension (.obj, .ply, .gltf or .glb, case-insensitive); throws
// Error(path, ...) for any other, for a missing file, or a folder.
LoadedMesh load_mesh_file(const std::filesystem::path& path, Diagnostics& diag);

}  // namespace sombra
