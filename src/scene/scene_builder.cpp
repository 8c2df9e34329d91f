#include "scene/scene_builder.h"

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "scene/corner_attributes.h"

namespace sombra {

namespace {

std::uint32_t u32(std::size_t n) { return static_cast<std::uint32_t>(n); }

// A triangle's material index that names no material (scene_material maps it to the default).
constexpr std::uint32_t kNoMaterialId = 0xffffffffu;

bool has_no_geometry(const TriangleMesh& m) {
    for (const UvSet& set : m.extra_uvs)
        if (!set.uvs.empty() || !set.indices.empty()) return false;
    return m.positions.empty() && m.triangles.empty() && m.normals.empty() && m.normal_indices.empty() &&
           m.uvs.empty() && m.uv_indices.empty() && m.tangents.empty() && m.tangent_indices.empty() &&
           m.colors.empty() && m.color_indices.empty() && m.material_ids.empty();
}

bool indices_in_range(const TriangleMesh& mesh) {
    const auto vertex_count = u32(mesh.positions.size());
    for (const Index3& t : mesh.triangles)
        if (t[0] >= vertex_count || t[1] >= vertex_count || t[2] >= vertex_count) return false;
    return true;
}

}  // namespace

MeshSizes sizes_of(const TriangleMesh& mesh) {
    return MeshSizes{mesh.positions.size(), mesh.triangles.size(), mesh.normals.size(), mesh.uvs.size(),
                     mesh.tangents.size(),  mesh.colors.size(),    mesh.has_normals(),  mesh.has_uvs(),
                     mesh.has_tangents(),   mesh.has_colors()};
}

MeshSizes& operator+=(MeshSizes& sum, const MeshSizes& more) {
    sum.positions += more.positions;
    sum.triangles += more.triangles;
    sum.normals += more.normals;
    sum.uvs += more.uvs;
    sum.tangents += more.tangents;
    sum.colors += more.colors;
    sum.any_normals = sum.any_normals || more.any_normals;
    sum.any_uvs = sum.any_uvs || more.any_uvs;
    sum.any_tangents = sum.any_tangents || more.any_tangents;
    sum.any_colors = sum.any_colors || more.any_colors;
    return sum;
}

std::uint32_t SceneBuilder::add_texture(Texture texture) {
    return sombra::add_texture(scene_.textures, std::move(texture));
}

std::uint32_t SceneBuilder::add_material(Material material) {
    material.textured = any_texture(material.textures);
    scene_.materials.push_back(std::move(material));
    return u32(scene_.materials.size() - 1);
}

std::uint32_t SceneBuilder::add_materials(std::span<const Material> materials, std::span<const Texture> textures) {
    const std::size_t first = scene_.materials.size();
    scene_.materials.insert(scene_.materials.end(), materials.begin(), materials.end());
    std::vector<std::uint32_t> texture_index(textures.size());
    for (std::size_t i = 0; i < textures.size(); ++i)
        texture_index[i] = sombra::add_texture(scene_.textures, textures[i]);
    renumber_textures(first, texture_index);
    return u32(first);
}

void SceneBuilder::renumber_textures(std::size_t first, const std::vector<std::uint32_t>& texture_index) {
    for (std::size_t i = first; i < scene_.materials.size(); ++i) {
        MaterialTextures& t = scene_.materials[i].textures;
        for_each_texture_ref(t, [&](TextureRef& r) {
            if (r.is_set()) r.texture = r.texture < texture_index.size() ? texture_index[r.texture] : kNoTexture;
        });
        scene_.materials[i].textured = any_texture(t);
    }
}

std::uint32_t SceneBuilder::scene_material(std::uint32_t id, MaterialJoin& join) {
    if (id < join.count) return join.base + id;
    // Readers give every face a material; a triangle without one still gets
    // the default, added once, rather than an index past the table.
    if (!join.fallback) {
        join.fallback = u32(scene_.materials.size());
        scene_.materials.push_back(default_material());
    }
    return *join.fallback;
}

void SceneBuilder::reserve(const MeshSizes& s) {
    TriangleMesh& w = scene_.geometry;
    const std::size_t triangles = w.triangles.size() + s.triangles;
    // A per-corner attribute's values, and its corner indices (one entry a
    // triangle), when some mesh to come has it.
    auto attribute = [triangles](bool any, auto& values, std::size_t more, std::vector<Index3>& indices) {
        if (!any) return;
        values.reserve(values.size() + more);
        indices.reserve(triangles);
    };
    w.positions.reserve(w.positions.size() + s.positions);
    w.triangles.reserve(triangles);
    w.material_ids.reserve(w.material_ids.size() + s.triangles);
    attribute(s.any_normals, w.normals, s.normals, w.normal_indices);
    attribute(s.any_uvs, w.uvs, s.uvs, w.uv_indices);
    attribute(s.any_tangents, w.tangents, s.tangents, w.tangent_indices);
    attribute(s.any_colors, w.colors, s.colors, w.color_indices);
}

void SceneBuilder::add_object(SceneObject object, const MeshPlacement& placement) {
    if (placement.media) {
        object.bounds_medium = true;
        object.interior = placement.media->interior;
        object.exterior = placement.media->exterior;
    }
    scene_.objects.push_back(std::move(object));
}

std::uint32_t SceneBuilder::interface_material() {
    if (scene_.interface_material == kNoInterface) {
        Material m;
        m.name = "interface";
        m.type = MaterialType::Interface;
        scene_.interface_material = add_material(std::move(m));
    }
    return scene_.interface_material;
}

MeshProblem SceneBuilder::add_mesh(const TriangleMesh& in, std::span<const Material> materials,
                                   std::span<const Texture> textures, const MeshPlacement& placement) {
    add_object(SceneObject{placement.name, placement.file, u32(scene_.geometry.triangles.size()),
                           u32(in.triangles.size())},
               placement);
    return append_mesh(scene_.geometry, in, materials, textures, placement.transform, placement.material);
}

MeshProblem SceneBuilder::append_mesh(TriangleMesh& out, const TriangleMesh& in, std::span<const Material> materials,
                                      std::span<const Texture> textures, const std::optional<Transform>& transform,
                                      std::optional<std::uint32_t> material) {
    const auto position_base = u32(out.positions.size());
    if (transform) {
        for (const Vec3 p : in.positions) {
            const Vec3 q = transform_point(*transform, p);
            // Non-finite input positions are the reader's to drop (their
            // triangles are gone); finite ones must stay finite.
            if (is_finite(p) && !is_finite(q)) return MeshProblem::NonFinitePlacement;
            out.positions.push_back(q);
        }
    } else {
        out.positions.insert(out.positions.end(), in.positions.begin(), in.positions.end());
    }

    // A mirroring transform (negative determinant) reverses every triangle's
    // winding; swapping two corners restores it, so the winding normal keeps
    // its side of the surface (spec §11, "sides for glass"). The normal, uv,
    // tangent and colour corners swap with them (append_corner_attributes).
    const bool mirrored = transform && determinant3(*transform) < 0;
    const auto vertex_count = u32(in.positions.size());
    for (Index3 t : in.triangles) {
        if (t[0] >= vertex_count || t[1] >= vertex_count || t[2] >= vertex_count) return MeshProblem::BadVertexIndex;
        if (mirrored) std::swap(t[1], t[2]);
        out.triangles.push_back({t[0] + position_base, t[1] + position_base, t[2] + position_base});
    }
    if (transform)
        append_corner_attributes(out, in, *transform);
    else
        append_corner_attributes(out, in);

    if (material) {
        out.material_ids.insert(out.material_ids.end(), in.triangles.size(), *material);
        return MeshProblem::None;
    }
    MaterialJoin join{add_materials(materials, textures), materials.size(), std::nullopt};
    for (std::size_t i = 0; i < in.triangles.size(); ++i)
        out.material_ids.push_back(
            scene_material(i < in.material_ids.size() ? in.material_ids[i] : kNoMaterialId, join));
    return MeshProblem::None;
}

MeshProblem SceneBuilder::add_instanced_mesh(const TriangleMesh& in, std::span<const Material> materials,
                                             std::span<const Texture> textures, const MeshPlacement& placement,
                                             std::span<const Transform> instances, std::size_t* bad_instance) {
    if (scene_.instances.size() + instances.size() > kMaxInstances) return MeshProblem::TooManyInstances;
    const auto mesh_index = u32(scene_.instanced_meshes.size());
    const auto object_index = u32(scene_.objects.size());
    add_object(SceneObject{placement.name, placement.file, u32(scene_.geometry.triangles.size()), 0,
                           u32(scene_.instances.size()), u32(instances.size())},
               placement);
    TriangleMesh& mesh = scene_.instanced_meshes.emplace_back();
    if (const MeshProblem p = append_mesh(mesh, in, materials, textures, std::nullopt, placement.material);
        p != MeshProblem::None)
        return p;

    // The mesh's bounds: an affine map keeps every vertex inside the placed
    // box's corners, so finite corners mean finite vertices.
    Vec3 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
    for (const Vec3 p : mesh.positions) {
        if (!is_finite(p)) continue;
        lo = min(lo, p);
        hi = max(hi, p);
    }
    scene_.instances.reserve(scene_.instances.size() + instances.size());
    for (std::size_t k = 0; k < instances.size(); ++k) {
        const Transform to_world = placement.transform ? compose(*placement.transform, instances[k]) : instances[k];
        const auto fail = [&](MeshProblem p) {
            if (bad_instance) *bad_instance = k;
            return p;
        };
        if (lo.x <= hi.x)
            for (int corner = 0; corner < 8; ++corner) {
                const Vec3 c{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
                if (!is_finite(transform_point(to_world, c))) return fail(MeshProblem::NonFinitePlacement);
            }
        Instance placed;
        placed.mesh = mesh_index;
        placed.object = object_index;
        if (placement.media) {
            const std::vector<std::uint32_t>& own = placement.media->instance_interiors;
            placed.interior = k < own.size() ? own[k] : placement.media->interior;
        }
        if (!place_instance(placed, to_world)) return fail(MeshProblem::SingularInstance);
        scene_.instances.push_back(placed);
    }
    return MeshProblem::None;
}

MeshProblem SceneBuilder::add_mesh(TriangleMesh&& mesh, std::vector<Material>&& materials,
                                   std::vector<Texture>&& textures, const MeshPlacement& placement) {
    if (placement.transform || !has_no_geometry(scene_.geometry))
        return add_mesh(std::as_const(mesh), materials, textures, placement);

    add_object(SceneObject{placement.name, placement.file, 0, u32(mesh.triangles.size())}, placement);
    if (!indices_in_range(mesh)) return MeshProblem::BadVertexIndex;
    scene_.geometry = std::move(mesh);
    std::vector<std::uint32_t>& ids = scene_.geometry.material_ids;
    const std::size_t triangles = scene_.geometry.triangles.size();
    if (placement.material) {
        ids.assign(triangles, *placement.material);
        return MeshProblem::None;
    }
    // The tables join as add_materials joins them, textures moved, not copied.
    const std::size_t first = scene_.materials.size();
    const std::size_t count = materials.size();
    scene_.materials.insert(scene_.materials.end(), std::make_move_iterator(materials.begin()),
                            std::make_move_iterator(materials.end()));
    std::vector<std::uint32_t> texture_index(textures.size());
    for (std::size_t i = 0; i < textures.size(); ++i)
        texture_index[i] = sombra::add_texture(scene_.textures, std::move(textures[i]));
    renumber_textures(first, texture_index);
    // The mesh's own indices become the scene's in place.
    MaterialJoin join{u32(first), count, std::nullopt};
    ids.resize(triangles, kNoMaterialId);
    for (std::uint32_t& id : ids) id = scene_material(id, join);
    return MeshProblem::None;
}

Scene SceneBuilder::finish() {
    mark_complete_corners(scene_.geometry);
    for (TriangleMesh& mesh : scene_.instanced_meshes) mark_complete_corners(mesh);
    Scene scene = std::move(scene_);
    scene_ = Scene{};
    return scene;
}

}  // namespace sombra
