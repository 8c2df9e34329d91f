// glTF 2.0 → LoadedMesh (spec §13, §23): the default scene's node tree
// walked from its roots, each node's transform composed parent × child,
// every triangle primitive of a mesh drawn once placed in the file's world
// space, a mesh drawn more often (several nodes, EXT_mesh_gpu_instancing)
// kept once with its instances, plus the lights and the first camera.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "io/gltf/gltf.h"
#include "io/mesh_builder.h"
#include "io/mesh_file.h"
#include "scene/scene_builder.h"
#include "scene/transform.h"

namespace sombra {

namespace {

using gltf::PrimitiveData;
using gltf::Primitives;

// Triangles built: a mesh drawn once is copied into the file's world, an
// instanced one stored once, so this bounds what a small file can ask for.
constexpr std::size_t kMaxInstancedTriangles = std::size_t{1} << 26;

struct NodePlacement {
    int node;
    Transform world;  // node → the file's world space
};

std::string node_name(int node) { return "node " + std::to_string(node); }

// The node's local transform (glTF 2.0 §3.5.3): its matrix (column-major),
// or T · R · S. Throws for non-finite values or a projective matrix.
Transform local_transform(const tinygltf::Node& n, int index, const std::string& file) {
    const auto all_finite = [](const std::vector<double>& v) {
        return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(static_cast<float>(x)); });
    };
    if (!all_finite(n.matrix) || !all_finite(n.translation) || !all_finite(n.rotation) || !all_finite(n.scale))
        throw Error(file, node_name(index) + ": the transform is not finite");
    Transform t;
    if (!n.matrix.empty()) {
        if (n.matrix.size() != 16) throw Error(file, node_name(index) + ": matrix must have 16 numbers");
        for (std::size_t row = 0; row < 4; ++row)
            for (std::size_t col = 0; col < 4; ++col) t.m[row * 4 + col] = float(n.matrix[col * 4 + row]);
        if (t.m[12] != 0 || t.m[13] != 0 || t.m[14] != 0 || t.m[15] != 1)
            throw Error(file, node_name(index) + ": matrix's last row must be [0, 0, 0, 1]");
        return t;
    }
    if ((!n.translation.empty() && n.translation.size() != 3) || (!n.scale.empty() && n.scale.size() != 3) ||
        (!n.rotation.empty() && n.rotation.size() != 4))
        throw Error(file, node_name(index) + ": translation and scale need 3 numbers, rotation 4");
    const Vec3 s = n.scale.empty() ? Vec3{1.0f} : Vec3{float(n.scale[0]), float(n.scale[1]), float(n.scale[2])};
    const Vec3 translation = n.translation.empty()
                                 ? Vec3{0.0f}
                                 : Vec3{float(n.translation[0]), float(n.translation[1]), float(n.translation[2])};
    const std::optional<Transform> trs =
        n.rotation.empty()
            ? gltf::trs_transform(translation, 0, 0, 0, 1, s)
            : gltf::trs_transform(translation, n.rotation[0], n.rotation[1], n.rotation[2], n.rotation[3], s);
    if (!trs) throw Error(file, node_name(index) + ": rotation is not a unit quaternion");
    return *trs;
}

// Every node the scene reaches, parents before children, with its world
// transform. Throws for a child index out of range, a node with two
// parents, a cycle, or a root that is someone's child.
std::vector<NodePlacement> walk_nodes(const tinygltf::Model& model, const std::string& file, Diagnostics& diag) {
    const std::size_t count = model.nodes.size();
    std::vector<int> parent(count, -1);
    for (std::size_t i = 0; i < count; ++i)
        for (const int child : model.nodes[i].children) {
            if (child < 0 || static_cast<std::size_t>(child) >= count)
                throw Error(file, node_name(int(i)) + " names child " + std::to_string(child) + ", but the file has " +
                                      std::to_string(count) + " nodes");
            if (parent[std::size_t(child)] != -1)
                throw Error(file, node_name(child) + " has two parents (" + node_name(parent[std::size_t(child)]) +
                                      " and " + node_name(int(i)) + "): the nodes must form trees");
            parent[std::size_t(child)] = int(i);
        }
    // With one parent each, a cycle is a parent chain that never ends.
    std::vector<char> state(count, 0);  // 0 unseen, 1 on the current chain, 2 ends at a root
    std::vector<int> chain;
    for (std::size_t start = 0; start < count; ++start) {
        chain.clear();
        int n = int(start);
        while (n != -1 && state[std::size_t(n)] == 0) {
            state[std::size_t(n)] = 1;
            chain.push_back(n);
            n = parent[std::size_t(n)];
        }
        if (n != -1 && state[std::size_t(n)] == 1)
            throw Error(file, node_name(n) + " is its own ancestor (a node cycle)");
        for (const int c : chain) state[std::size_t(c)] = 2;
    }

    std::vector<int> roots;
    if (model.scenes.empty()) {
        for (std::size_t i = 0; i < count; ++i)
            if (parent[i] == -1) roots.push_back(int(i));
        if (!roots.empty()) diag.warn(file, "the file has no scene: every root node is loaded");
    } else {
        const int scene = model.defaultScene < 0 ? 0 : model.defaultScene;
        if (static_cast<std::size_t>(scene) >= model.scenes.size())
            throw Error(file, "the default scene " + std::to_string(scene) + " does not exist");
        roots = model.scenes[std::size_t(scene)].nodes;
    }
    std::vector<NodePlacement> out;
    std::vector<bool> seen(count, false);
    std::vector<NodePlacement> stack;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) {
        if (*root < 0 || static_cast<std::size_t>(*root) >= count)
            throw Error(file, "the scene names " + node_name(*root) + ", but the file has " + std::to_string(count) +
                                  " nodes");
        if (parent[std::size_t(*root)] != -1)
            throw Error(file, "the scene's root " + node_name(*root) + " is a child of " +
                                  node_name(parent[std::size_t(*root)]));
        stack.push_back({*root, Transform{}});
    }
    while (!stack.empty()) {
        NodePlacement top = stack.back();
        stack.pop_back();
        if (seen[std::size_t(top.node)]) throw Error(file, "the scene lists " + node_name(top.node) + " twice");
        seen[std::size_t(top.node)] = true;
        const tinygltf::Node& n = model.nodes[std::size_t(top.node)];
        top.world = compose(local_transform(n, top.node, file), top.world);
        out.push_back(top);
        for (auto child = n.children.rbegin(); child != n.children.rend(); ++child)
            stack.push_back({*child, top.world});
    }
    return out;
}

// Appends a primitive to the builder, placed by `world` (none: as it is,
// for a mesh stored once and drawn by instances).
void append_primitive(MeshBuilder& b, const PrimitiveData& p, const std::optional<Transform>& world,
                      std::uint32_t material) {
    const auto base = static_cast<std::uint32_t>(b.positions.size());
    const auto normal_base = static_cast<std::uint32_t>(b.normals.size());
    const auto uv_base = static_cast<std::uint32_t>(b.uvs.size());
    const auto tangent_base = static_cast<std::uint32_t>(b.tangents.size());
    const auto color_base = static_cast<std::uint32_t>(b.colors.size());
    std::array<std::uint32_t, kUvSets - 1> extra_base{};
    for (std::size_t k = 0; k < extra_base.size(); ++k) {
        extra_base[k] = static_cast<std::uint32_t>(b.extra_uvs[k].size());
        b.extra_uvs[k].insert(b.extra_uvs[k].end(), p.extra_uvs[k].begin(), p.extra_uvs[k].end());
    }
    if (world) {
        for (const Vec3 v : p.positions) b.positions.push_back(transform_point(*world, v));
        const Transform to_world = normal_transform(*world);
        for (const Vec3 n : p.normals) b.normals.push_back(transform_vector(to_world, n));
    } else {
        b.positions.insert(b.positions.end(), p.positions.begin(), p.positions.end());
        b.normals.insert(b.normals.end(), p.normals.begin(), p.normals.end());
    }
    b.uvs.insert(b.uvs.end(), p.uvs.begin(), p.uvs.end());
    // A mirroring node (negative determinant) reverses the winding; swapping
    // two corners restores it, so the dielectric's outside stays outside (§11).
    // (Instances are the scene builder's to mirror.)
    const bool mirrored = world && determinant3(*world) < 0;
    // Tangents are surface directions: they move with the linear part. The
    // mirror also turns M·(n × t) into −(M⁻ᵀn × Mt) (up to positive
    // factors), so the handedness flips for bitangent = w·(n × t) to keep
    // following the mirrored surface.
    for (const VertexTangent& t : p.tangents)
        b.tangents.push_back(
            {world ? transform_vector(*world, t.direction) : t.direction, mirrored ? -t.handedness : t.handedness});
    b.colors.insert(b.colors.end(), p.colors.begin(), p.colors.end());
    const auto corners = [](bool present, std::uint32_t first, const std::uint32_t(&c)[3], std::uint32_t(&out)[3]) {
        for (int k = 0; k < 3; ++k) out[k] = first + c[k];
        return present ? std::span<const std::uint32_t>(out) : std::span<const std::uint32_t>{};
    };
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        std::uint32_t c[3] = {p.indices[t], p.indices[t + 1], p.indices[t + 2]};
        if (mirrored) std::swap(c[1], c[2]);
        std::uint32_t pos[3], nor[3], uv[3], tan[3], col[3], extra_uv[kUvSets - 1][3];
        MeshBuilder::ExtraUvCorners extra;
        for (std::size_t k = 0; k < extra.size(); ++k)
            extra[k] = corners(!p.extra_uvs[k].empty(), extra_base[k], c, extra_uv[k]);
        b.add_face(corners(true, base, c, pos), corners(!p.normals.empty(), normal_base, c, nor), material,
                   corners(!p.uvs.empty(), uv_base, c, uv), corners(!p.tangents.empty(), tangent_base, c, tan),
                   corners(!p.colors.empty(), color_base, c, col), extra);
    }
}

// Appends a mesh's primitives (see append_primitive); returns whether any
// has a triangle.
bool append_mesh(MeshBuilder& b, const Primitives& primitives, const std::optional<Transform>& world,
                 const std::string& file) {
    bool any = false;
    for (const std::optional<PrimitiveData>& p : primitives) {
        if (!p) continue;
        const std::uint32_t material = p->material < 0 ? kNoMaterial : std::uint32_t(p->material);
        if (b.positions.size() + p->positions.size() >= kNoNormal)
            throw Error(file, "the scene has more than " + std::to_string(kNoNormal - 1) + " vertices");
        append_primitive(b, *p, world, material);
        any = any || p->indices.size() >= 3;
    }
    return any;
}

// A mesh drawn more than once, while it is assembled.
struct PartBuild {
    MeshBuilder builder;
    InstancedPart part;  // all but the mesh
};

}  // namespace

LoadedMesh load_gltf(const std::filesystem::path& path, Diagnostics& diag) {
    const std::string file = path.string();
    const tinygltf::Model model = gltf::parse_file(path, diag);
    const auto uses = [&](const char* ext) {
        return std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), ext) != model.extensionsUsed.end();
    };
    const gltf::AccessorReader reader{model, file, uses(gltf::kQuantization)};
    const std::vector<NodePlacement> placements = walk_nodes(model, file, diag);
    gltf::Materials materials = gltf::convert_materials(model, file, diag);
    std::map<std::string, std::size_t> skipped;  // what was skipped → how often

    // Animations (spec §22): a node moves when a channel targets it or an
    // ancestor. What it draws is an instanced part (even when drawn once),
    // placed as at time 0; so are its camera and lights, which follow their
    // nodes too (LoadedMesh::light_nodes, camera_node).
    std::vector<std::uint32_t> order;
    for (const NodePlacement& in : placements) order.push_back(std::uint32_t(in.node));
    std::shared_ptr<const GltfNodeAnimation> animation = gltf::read_animations(reader, order, skipped);
    const gltf::Motion motion = gltf::motion_of(animation.get(), model.nodes.size());
    const std::vector<char>& animated = motion.moving;
    const auto world_of = [&](const NodePlacement& in) {
        return animated[std::size_t(in.node)] ? motion.at_start[std::size_t(in.node)] : in.world;
    };

    // How often each mesh is drawn: once per node, or once per instance of
    // a node with EXT_mesh_gpu_instancing. Nodes scaled to nothing are
    // invisible (unless animated: they may grow).
    const auto visible = [&](const NodePlacement& in) {
        return animated[std::size_t(in.node)] || std::fabs(determinant3(in.world)) > 0.0f;
    };
    std::map<int, std::vector<Transform>> gpu;  // node → its instances, in its own coordinates
    std::vector<std::size_t> drawings(model.meshes.size(), 0);
    std::vector<bool> named(model.meshes.size(), false);  // by any node: its accessors are checked
    std::size_t instance_total = 0;
    for (const NodePlacement& in : placements) {
        const tinygltf::Node& node = model.nodes[std::size_t(in.node)];
        std::vector<Transform> local = gltf::gpu_instances(reader, node, in.node, kMaxInstances - instance_total);
        const int m = node.mesh;
        if (m < 0) continue;
        if (static_cast<std::size_t>(m) >= model.meshes.size())
            throw Error(file, node_name(in.node) + " names mesh " + std::to_string(m) + ", but the file has " +
                                  std::to_string(model.meshes.size()));
        named[std::size_t(m)] = true;
        if (!visible(in)) continue;
        const std::size_t n = node.extensions.count(gltf::kGpuInstancing) ? local.size() : 1;
        drawings[std::size_t(m)] += n;
        instance_total += n;
        if (instance_total > kMaxInstances)
            throw Error(file, "the scene draws meshes more than " + std::to_string(kMaxInstances) + " times");
        if (!local.empty()) gpu.emplace(in.node, std::move(local));
    }
    std::size_t triangles = 0;
    for (std::size_t m = 0; m < drawings.size(); ++m) {
        if (!named[m]) continue;
        std::size_t count = 0;
        for (const tinygltf::Primitive& p : model.meshes[m].primitives) {
            const int counted =
                p.indices >= 0 ? p.indices : (p.attributes.count("POSITION") ? p.attributes.at("POSITION") : -1);
            if (p.mode == TINYGLTF_MODE_TRIANGLES && counted >= 0)
                count += gltf::accessor_count(reader, counted, "mesh " + std::to_string(m)) / 3;
        }
        // A mesh drawn once is copied once, one drawn more often stored once.
        triangles += count;
        if (triangles > kMaxInstancedTriangles)
            throw Error(file, "the scene places more than " + std::to_string(kMaxInstancedTriangles) + " triangles");
    }

    MeshBuilder builder(file);
    std::map<int, Primitives> decoded;   // mesh → its primitives, read once
    std::map<int, std::size_t> part_of;  // instanced mesh → its index in parts
    std::vector<PartBuild> parts;
    std::optional<std::pair<int, ModelCamera>> camera;  // the lowest camera index placed
    std::vector<PunctualLight> lights;
    // What an animated node carries (LoadedMesh::light_nodes, camera_node).
    std::vector<int> light_nodes;
    std::vector<PunctualLight> lights_in_nodes;
    int camera_node = -1;
    bool any_triangles = false;
    std::size_t clamped_colors = 0;
    std::size_t missing_texcoords = 0;  // primitives without a TEXCOORD_k their material's textures read
    for (const NodePlacement& in : placements) {
        const tinygltf::Node& node = model.nodes[std::size_t(in.node)];
        if (node.skin >= 0) ++skipped["skins (the bind pose is used)"];
        if (node.camera >= 0 && (!camera || node.camera < camera->first))
            if (std::optional<ModelCamera> c = gltf::place_camera(model, node.camera, world_of(in), file, diag)) {
                camera = {node.camera, *c};
                camera_node = animated[std::size_t(in.node)] ? in.node : -1;
            }
        PunctualLight in_node;
        if (std::optional<PunctualLight> l =
                gltf::place_light(model, node, in.node, world_of(in), file, diag, skipped, in_node)) {
            lights.push_back(*l);
            light_nodes.push_back(animated[std::size_t(in.node)] ? in.node : -1);
            lights_in_nodes.push_back(in_node);
        }
        if (node.mesh < 0 || !visible(in)) continue;
        auto [cached, first_use] = decoded.try_emplace(node.mesh);
        if (first_use) {
            cached->second = gltf::read_mesh(reader, node.mesh, materials.materials.size(), skipped, clamped_colors);
            for (const std::optional<gltf::PrimitiveData>& p : cached->second)
                if (p && p->material >= 0 && gltf::lacks_texcoord(*p, materials.texture_refs[std::size_t(p->material)]))
                    ++missing_texcoords;
        }
        const Primitives& primitives = cached->second;
        const auto local = gpu.find(in.node);
        const bool gpu_instanced = node.extensions.count(gltf::kGpuInstancing) > 0;
        if (gpu_instanced && local == gpu.end()) continue;  // no instances (count 0 is the accessor's error)
        const bool moves = animated[std::size_t(in.node)] != 0;
        if (drawings[std::size_t(node.mesh)] == 1 && !moves) {
            const Transform world = gpu_instanced ? compose(local->second[0], in.world) : in.world;
            any_triangles = append_mesh(builder, primitives, world, file) || any_triangles;
            continue;
        }
        const auto [index, new_part] = part_of.try_emplace(node.mesh, parts.size());
        if (new_part) {
            parts.push_back(PartBuild{MeshBuilder(file), {}});
            any_triangles = append_mesh(parts.back().builder, primitives, std::nullopt, file) || any_triangles;
        }
        InstancedPart& part = parts[index->second].part;
        part.origins.push_back({part.instances.size(), node_name(in.node), gpu_instanced});
        const Transform world = world_of(in);
        if (moves && !(std::fabs(determinant3(world)) > 0.0f))
            throw Error(file, node_name(in.node) + ": its animated transform at time 0 is not invertible");
        // In a file with animations every part follows its nodes (a static node's pose is its rest pose).
        const std::size_t first_instance = part.instances.size();
        const auto add = [&](const Transform& before) {
            const Transform placed = compose(before, world);
            // The ray transform needs an inverse in float: a product of
            // tiny (or huge) scales can lose it though each factor has one.
            if (Instance probe; !place_instance(probe, placed))
                throw Error(file,
                            node_name(in.node) +
                                (gpu_instanced ? ": instance " + std::to_string(part.instances.size() - first_instance)
                                               : std::string()) +
                                ": the transform is not invertible");
            part.instances.push_back(placed);
            if (!animation) return;
            part.nodes.push_back(std::uint32_t(in.node));
            part.local.push_back(before);
        };
        if (!gpu_instanced) {
            add(Transform{});
            continue;
        }
        // The instance's T · R · S first, then the node's transform (the extension's order).
        for (const Transform& t : local->second) add(t);
    }
    if (!any_triangles) {
        std::string list;
        for (const auto& [what, count] : skipped) list += (list.empty() ? "; skipped " : ", ") + what;
        throw Error(file, "the default scene has no triangles to draw" + list);
    }
    for (const auto& [what, count] : skipped) diag.warn(file, "skipped " + what + " (" + std::to_string(count) + ")");
    if (clamped_colors > 0)
        diag.warn(file, "COLOR_0: " + std::to_string(clamped_colors) + " components outside [0, 1] clamped");
    if (missing_texcoords > 0)
        diag.warn(file, std::to_string(missing_texcoords) +
                            " primitives lack a TEXCOORD_n that their material's textures read: those textures are "
                            "not applied there (their constants are used)");

    // The meshes' material ids index one list; a face without a material
    // gets the default, added once at its end.
    LoadedMesh out;
    const std::size_t material_count = materials.materials.size();
    bool uses_default = false;
    if (builder.triangle_count() > 0 || parts.empty())
        out.mesh = builder.finish_mesh(material_count, uses_default, diag);
    for (PartBuild& p : parts) {
        if (p.builder.triangle_count() == 0) continue;  // every primitive skipped
        p.part.mesh = p.builder.finish_mesh(material_count, uses_default, diag);
        out.instanced.push_back(std::move(p.part));
    }
    if (uses_default) materials.materials.push_back(default_material());
    out.materials = std::move(materials.materials);
    materials.texture_refs.resize(out.materials.size());  // the default material, if added, has none
    gltf::apply_textures(model, path, materials.texture_refs, out.materials, out.textures, diag);
    out.lights = std::move(lights);
    if (camera) out.camera = camera->second;
    const bool carried =
        camera_node >= 0 || std::any_of(light_nodes.begin(), light_nodes.end(), [](int n) { return n >= 0; });
    if (carried) {
        out.light_nodes = std::move(light_nodes);
        out.lights_in_nodes = std::move(lights_in_nodes);
        out.camera_node = camera_node;
    }
    const bool any_moving = std::any_of(out.instanced.begin(), out.instanced.end(),
                                        [](const InstancedPart& p) { return !p.nodes.empty(); }) ||
                            carried;
    if (any_moving) out.animation = std::move(animation);
    return out;
}

}  // namespace sombra
