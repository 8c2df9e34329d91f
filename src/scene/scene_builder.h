// Assembling a Scene (spec §2, §8): the one way the readers (io/) and the
// tests put a scene together, so that the rules for joining meshes live in
// one place: placement in world space (positions, normals, tangents; mirrors
// keep their winding), the meshes' materials and textures joining the
// scene's tables with their indices renumbered, one SceneObject per mesh,
// and the per-triangle bits shading reads (corner_attributes.h).
//
//     SceneBuilder b;
//     b.set_camera(camera);
//     const std::uint32_t grey = b.add_material(Material{"grey", MaterialType::Diffuse, Vec3{0.5f}});
//     b.add_light(make_point_light({0, 4, 0}, Vec3{10.0f}));
//     MeshPlacement floor{"floor", "floor.obj", make_scale(Vec3{2.0f}), grey};
//     if (b.add_mesh(mesh, {}, {}, floor) != MeshProblem::None) ...;  // arrays in their own coordinates
//     Scene scene = b.finish();
//
// Plain data in, plain data out: no files, no JSON, no messages. A reader
// turns a MeshProblem into its own error, naming the place in its file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/scene.h"
#include "scene/texture.h"
#include "scene/transform.h"

namespace sombra {

// How a mesh joins the scene.
// The media on the two sides of an object's surface (indices into
// Scene::media, kNoMedium: vacuum): SceneObject::interior and exterior.
struct MediumBoundary {
    std::uint32_t interior = kNoMedium;
    std::uint32_t exterior = kNoMedium;
    // For add_instanced_mesh: each instance's own interior (Instance::
    // interior, a grid placed per drawing), one per instance; empty: `interior`.
    std::vector<std::uint32_t> instance_interiors{};
};

struct MeshPlacement {
    std::string name;  // SceneObject::name: the scene file's JSON pointer, or the model's file name
    std::string file;  // SceneObject::file: the mesh file; "" when there is none (a quad light)
    // The mesh's coordinates → world space. Unset: the mesh is in world
    // space already and joins bit for bit as it is (any transform, the
    // identity too, renormalises normals and turns −0 into +0).
    std::optional<Transform> transform;
    // Set: every triangle gets this material, an index into Scene::materials,
    // and the mesh's own materials and textures are not added.
    std::optional<std::uint32_t> material;
    // Set: the mesh bounds a medium (spec §26), SceneObject's interior and exterior.
    std::optional<MediumBoundary> media{};
};

// What add_mesh found wrong with a mesh. The scene then holds part of the
// mesh and is unusable: the caller reports the problem and abandons it.
enum class MeshProblem {
    None,
    NonFinitePlacement,  // a finite vertex is infinite or NaN once transformed
    BadVertexIndex,      // a triangle names a vertex the mesh does not have
    SingularInstance,    // an instance's whole transform is not invertible in float (determinant 0 or overflowing)
    TooManyInstances,    // the scene would hold more than kMaxInstances instances
};

// Instances a scene may hold: each costs about 200 bytes, so a file's claim
// is bounded (1.7 GB) before anything is allocated for it.
inline constexpr std::size_t kMaxInstances = std::size_t{1} << 23;

// The array sizes of meshes still to come, summed with +=, for reserve().
struct MeshSizes {
    std::size_t positions = 0, triangles = 0, normals = 0, uvs = 0, tangents = 0, colors = 0;
    bool any_normals = false, any_uvs = false, any_tangents = false, any_colors = false;
};
MeshSizes sizes_of(const TriangleMesh& mesh);
MeshSizes& operator+=(MeshSizes& sum, const MeshSizes& more);

class SceneBuilder {
public:
    void set_camera(const CameraSpec& camera) { scene_.camera = camera; }
    void set_background(Vec3 background) { scene_.background = background; }
    // The environment map replaces the background (spec §10).
    void set_environment(EnvironmentMap environment) { scene_.environment = std::move(environment); }
    // A light in world space, after those added before it.
    void add_light(const PunctualLight& light) { scene_.lights.push_back(light); }
    // Participating media (spec §26), and the index of the one that fills
    // the space outside every object (kNoMedium: none).
    void set_media(std::vector<Medium> media, std::uint32_t render_medium) {
        scene_.media = std::move(media);
        scene_.render_medium = render_medium;
    }
    // Adds a medium after those set_media gave; returns its index.
    std::uint32_t add_medium(Medium medium) {
        scene_.media.push_back(std::move(medium));
        return static_cast<std::uint32_t>(scene_.media.size() - 1);
    }
    // The medium the camera sits in when it is not the render medium.
    void set_camera_medium(std::uint32_t medium) { scene_.camera_medium = medium; }
    // The index of the "interface" material (spec §26), added on first use.
    std::uint32_t interface_material();

    // Adds a texture to Scene::textures and returns its index; a texture with
    // the same source and encoding as one already there is shared (add_texture).
    std::uint32_t add_texture(Texture texture);
    // Adds a material whose TextureRefs index Scene::textures and returns its
    // index into Scene::materials; `textured` is set from its references.
    std::uint32_t add_material(Material material);
    // Adds materials whose TextureRefs index `textures`, their own table
    // (a mesh file's): the textures join Scene::textures (shared by source
    // and encoding), the references are renumbered, `textured` set. Returns
    // the index of the first material in Scene::materials.
    std::uint32_t add_materials(std::span<const Material> materials, std::span<const Texture> textures);

    // Makes room for meshes of these sizes, so that the world arrays grow once.
    void reserve(const MeshSizes& sizes);

    // Adds a mesh given as arrays: its vertices and per-corner attributes
    // placed in world space by placement.transform (normals by the inverse
    // transpose, tangents by the linear part, both renormalised; a mirroring
    // transform swaps two corners of each triangle so that the winding keeps
    // its side, spec §11), its material_ids indexing `materials` (whose
    // TextureRefs index `textures`), which join the scene by add_materials;
    // a triangle naming no such material gets default_material(). Appends
    // the SceneObject placement names. Checks in this order, stopping at the
    // first problem: the placed positions, then the triangles' indices.
    [[nodiscard]] MeshProblem add_mesh(const TriangleMesh& mesh, std::span<const Material> materials,
                                       std::span<const Texture> textures, const MeshPlacement& placement);
    // The same for a mesh not needed afterwards. Into a scene without
    // geometry, a mesh without a transform moves in whole instead of being
    // copied (a quick look at a huge model then holds it once), and so do
    // its textures.
    [[nodiscard]] MeshProblem add_mesh(TriangleMesh&& mesh, std::vector<Material>&& materials,
                                       std::vector<Texture>&& textures, const MeshPlacement& placement);

    // Adds a mesh drawn once per entry of `instances` (spec §23), stored once
    // in its own coordinates (materials and textures join as add_mesh's).
    // Instance k's object-to-world matrix is instances[k] applied after
    // placement.transform (when set). Appends one SceneObject naming the
    // instances. Checks the triangles' indices, then each instance in
    // order: its matrix invertible and the mesh's vertices finite once
    // placed; on a problem with instance k, `bad_instance` (when given)
    // receives k. At most kMaxInstances in a scene.
    [[nodiscard]] MeshProblem add_instanced_mesh(const TriangleMesh& mesh, std::span<const Material> materials,
                                                 std::span<const Texture> textures, const MeshPlacement& placement,
                                                 std::span<const Transform> instances,
                                                 std::size_t* bad_instance = nullptr);

    // The scene so far (the readers look up what they added).
    const Scene& scene() const { return scene_; }

    // The finished scene: TriangleMesh::complete_normals and complete_uvs
    // derived (mark_complete_corners). The builder is left empty.
    Scene finish();

private:
    // Appends `object`, with the placement's medium boundary when it has one.
    void add_object(SceneObject object, const MeshPlacement& placement);
    // Renumbers the TextureRefs of materials [first, end) by `texture_index`
    // (their own table's index → Scene::textures) and sets `textured`.
    void renumber_textures(std::size_t first, const std::vector<std::uint32_t>& texture_index);
    // A mesh's materials joining the scene: its material index i < count
    // becomes base + i; any other, the default material, added once.
    struct MaterialJoin {
        std::uint32_t base = 0;
        std::size_t count = 0;
        std::optional<std::uint32_t> fallback;
    };
    std::uint32_t scene_material(std::uint32_t id, MaterialJoin& join);
    // add_mesh's work, into `out` (the world geometry or an instanced mesh).
    MeshProblem append_mesh(TriangleMesh& out, const TriangleMesh& in, std::span<const Material> materials,
                            std::span<const Texture> textures, const std::optional<Transform>& transform,
                            std::optional<std::uint32_t> material);

    Scene scene_;
};

}  // namespace sombra
