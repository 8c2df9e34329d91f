// glTF 2.0 → LoadedMesh (spec §13): the default scene's node tree walked
// from its roots, each node's transform composed parent × child, every
// triangle primitive of every mesh instance placed in the file's world
// space, plus the lights and the first camera the tree places.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "io/gltf/gltf.h"
#include "io/mesh_builder.h"
#include "io/mesh_file.h"
#include "scene/transform.h"

namespace sombra {

namespace {

using gltf::PrimitiveData;

// Triangles over all mesh instances: one mesh placed by many nodes is copied
// for each, so this bounds what a small file can ask to build.
constexpr std::size_t kMaxInstancedTriangles = std::size_t{1} << 26;

struct Instance {
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
    double x = 0, y = 0, z = 0, w = 1;
    if (!n.rotation.empty()) {
        x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        const double len = std::sqrt(x * x + y * y + z * z + w * w);
        if (!(len > 1e-12) || !std::isfinite(len))
            throw Error(file, node_name(index) + ": rotation is not a unit quaternion");
        x /= len, y /= len, z /= len, w /= len;
    }
    // Rotation matrix of the unit quaternion (x, y, z, w), columns scaled by s.
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    const float scale[3] = {s.x, s.y, s.z};
    for (std::size_t row = 0; row < 3; ++row) {
        for (std::size_t col = 0; col < 3; ++col) t.m[row * 4 + col] = float(r[row][col]) * scale[col];
        t.m[row * 4 + 3] = n.translation.empty() ? 0.0f : float(n.translation[row]);
    }
    return t;
}

// Every node the scene reaches, parents before children, with its world
// transform. Throws for a child index out of range, a node with two
// parents, a cycle, or a root that is someone's child.
std::vector<Instance> walk_nodes(const tinygltf::Model& model, const std::string& file, Diagnostics& diag) {
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
    std::vector<Instance> out;
    std::vector<bool> seen(count, false);
    std::vector<Instance> stack;
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
        Instance top = stack.back();
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

// A primitive's attributes and indices, read and checked; v flipped.
PrimitiveData read_primitive(const gltf::AccessorReader& r, const tinygltf::Primitive& p, const std::string& what) {
    const auto attribute = [&](const char* name) {
        const auto it = p.attributes.find(name);
        return it == p.attributes.end() ? -1 : it->second;
    };
    if (attribute("POSITION") < 0) throw gltf::Unsupported{"primitives without POSITION"};
    PrimitiveData out;
    out.material = p.material;
    const std::vector<float> pos =
        read_floats(r, attribute("POSITION"), gltf::Semantic::Position, "POSITION of " + what);
    const std::size_t n = pos.size() / 3;
    if (n >= kNoNormal) throw Error(r.file, what + ": too many vertices");
    out.positions.resize(n);
    for (std::size_t i = 0; i < n; ++i) out.positions[i] = {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]};
    if (attribute("NORMAL") >= 0) {
        const std::vector<float> nor = read_floats(r, attribute("NORMAL"), gltf::Semantic::Normal, "NORMAL of " + what);
        if (nor.size() != pos.size()) throw Error(r.file, what + ": NORMAL and POSITION differ in count");
        out.normals.resize(n);
        for (std::size_t i = 0; i < n; ++i) out.normals[i] = {nor[3 * i], nor[3 * i + 1], nor[3 * i + 2]};
    }
    if (attribute("TEXCOORD_0") >= 0) {
        const std::vector<float> uv =
            read_floats(r, attribute("TEXCOORD_0"), gltf::Semantic::Texcoord, "TEXCOORD_0 of " + what);
        if (uv.size() / 2 != n) throw Error(r.file, what + ": TEXCOORD_0 and POSITION differ in count");
        out.uvs.resize(n);
        // glTF's v = 0 is the image's top row; sombra's uvs (like OBJ's) put v = 0 at the bottom.
        for (std::size_t i = 0; i < n; ++i) out.uvs[i] = {uv[2 * i], 1.0f - uv[2 * i + 1]};
    }
    if (attribute("TANGENT") >= 0) {
        const std::vector<float> t =
            read_floats(r, attribute("TANGENT"), gltf::Semantic::Tangent, "TANGENT of " + what);
        if (t.size() / 4 != n) throw Error(r.file, what + ": TANGENT and POSITION differ in count");
        out.tangents = gltf::tangents_of(t);
    }
    if (attribute("COLOR_0") >= 0) {
        const std::vector<float> c = read_floats(r, attribute("COLOR_0"), gltf::Semantic::Color, "COLOR_0 of " + what);
        if (c.size() / 4 != n) throw Error(r.file, what + ": COLOR_0 and POSITION differ in count");
        out.colors = gltf::colors_of(c, out.clamped_colors);
    }
    if (p.indices >= 0) {
        out.indices = read_indices(r, p.indices, n, "indices of " + what);
    } else {
        out.indices.resize(n);
        for (std::size_t i = 0; i < n; ++i) out.indices[i] = static_cast<std::uint32_t>(i);
    }
    return out;
}

// Appends one instance of a primitive, placed by `world`, to the builder.
void append_instance(MeshBuilder& b, const PrimitiveData& p, const Transform& world, std::uint32_t material) {
    const auto base = static_cast<std::uint32_t>(b.positions.size());
    const auto normal_base = static_cast<std::uint32_t>(b.normals.size());
    const auto uv_base = static_cast<std::uint32_t>(b.uvs.size());
    const auto tangent_base = static_cast<std::uint32_t>(b.tangents.size());
    const auto color_base = static_cast<std::uint32_t>(b.colors.size());
    for (const Vec3 v : p.positions) b.positions.push_back(transform_point(world, v));
    const Transform to_world = normal_transform(world);
    for (const Vec3 n : p.normals) b.normals.push_back(transform_vector(to_world, n));
    b.uvs.insert(b.uvs.end(), p.uvs.begin(), p.uvs.end());
    // A mirroring node (negative determinant) reverses the winding; swapping
    // two corners restores it, so the dielectric's outside stays outside (§11).
    const bool mirrored = determinant3(world) < 0;
    // Tangents are surface directions: they move with the linear part. The
    // mirror also turns M·(n × t) into −(M⁻ᵀn × Mt) (up to positive
    // factors), so the handedness flips for bitangent = w·(n × t) to keep
    // following the mirrored surface.
    for (const VertexTangent& t : p.tangents)
        b.tangents.push_back({transform_vector(world, t.direction), mirrored ? -t.handedness : t.handedness});
    b.colors.insert(b.colors.end(), p.colors.begin(), p.colors.end());
    const auto corners = [](bool present, std::uint32_t first, const std::uint32_t(&c)[3], std::uint32_t(&out)[3]) {
        for (int k = 0; k < 3; ++k) out[k] = first + c[k];
        return present ? std::span<const std::uint32_t>(out) : std::span<const std::uint32_t>{};
    };
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        std::uint32_t c[3] = {p.indices[t], p.indices[t + 1], p.indices[t + 2]};
        if (mirrored) std::swap(c[1], c[2]);
        std::uint32_t pos[3], nor[3], uv[3], tan[3], col[3];
        b.add_face(corners(true, base, c, pos), corners(!p.normals.empty(), normal_base, c, nor), material,
                   corners(!p.uvs.empty(), uv_base, c, uv), corners(!p.tangents.empty(), tangent_base, c, tan),
                   corners(!p.colors.empty(), color_base, c, col));
    }
}

// The camera `index` placed by `world`, or nothing (with a warning) when it
// is orthographic or degenerate.
std::optional<ModelCamera> place_camera(const tinygltf::Model& model, int index, const Transform& world,
                                        const std::string& file, Diagnostics& diag) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.cameras.size())
        throw Error(file, "a node names camera " + std::to_string(index) + ", but the file has " +
                              std::to_string(model.cameras.size()));
    const tinygltf::Camera& c = model.cameras[std::size_t(index)];
    if (c.type != "perspective") {
        diag.warn(file, "camera " + std::to_string(index) + " is " + c.type +
                            ", not perspective: the model is framed automatically");
        return std::nullopt;
    }
    const double yfov = c.perspective.yfov * 180.0 / std::numbers::pi;
    ModelCamera cam;
    cam.origin = transform_point(world, Vec3{0.0f});
    const Vec3 forward = transform_vector(world, Vec3{0, 0, -1});
    const Vec3 up = transform_vector(world, Vec3{0, 1, 0});
    cam.forward = normalize(forward);
    cam.up = normalize(up - dot(up, cam.forward) * cam.forward);
    cam.yfov_degrees = static_cast<float>(yfov);
    cam.aspect = c.perspective.aspectRatio > 0 ? static_cast<float>(c.perspective.aspectRatio) : 0.0f;
    if (!(yfov > 0 && yfov < 180) || !std::isfinite(cam.aspect) || !is_finite(cam.origin) || !is_finite(cam.forward) ||
        !is_finite(cam.up)) {
        diag.warn(file, "camera " + std::to_string(index) +
                            " is unusable (field of view, aspect or placement): the model is framed automatically");
        return std::nullopt;
    }
    return cam;
}

}  // namespace

LoadedMesh load_gltf(const std::filesystem::path& path, Diagnostics& diag) {
    const std::string file = path.string();
    const tinygltf::Model model = gltf::parse_file(path, diag);
    const auto uses = [&](const char* ext) {
        return std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), ext) != model.extensionsUsed.end();
    };
    const gltf::AccessorReader reader{model, file, uses(gltf::kQuantization)};
    const std::vector<Instance> instances = walk_nodes(model, file, diag);

    gltf::Materials materials = gltf::convert_materials(model, file, diag);
    std::map<std::string, std::size_t> skipped;  // what was skipped → how often
    std::size_t triangles = 0;
    for (const Instance& in : instances) {
        const int m = model.nodes[std::size_t(in.node)].mesh;
        if (m < 0) continue;
        if (static_cast<std::size_t>(m) >= model.meshes.size())
            throw Error(file, node_name(in.node) + " names mesh " + std::to_string(m) + ", but the file has " +
                                  std::to_string(model.meshes.size()));
        for (const tinygltf::Primitive& p : model.meshes[std::size_t(m)].primitives) {
            const int counted =
                p.indices >= 0 ? p.indices : (p.attributes.count("POSITION") ? p.attributes.at("POSITION") : -1);
            if (p.mode == TINYGLTF_MODE_TRIANGLES && counted >= 0)
                triangles += gltf::accessor_count(reader, counted, "mesh " + std::to_string(m)) / 3;
        }
        if (triangles > kMaxInstancedTriangles)
            throw Error(file, "the scene places more than " + std::to_string(kMaxInstancedTriangles) + " triangles");
    }

    MeshBuilder builder(file);
    std::map<int, std::vector<std::optional<PrimitiveData>>> decoded;  // mesh → its primitives, read once
    std::optional<std::pair<int, ModelCamera>> camera;                 // the lowest camera index placed
    std::vector<PunctualLight> lights;
    bool any_triangles = false;
    std::size_t clamped_colors = 0;
    for (const Instance& in : instances) {
        const tinygltf::Node& node = model.nodes[std::size_t(in.node)];
        if (node.skin >= 0) ++skipped["skins (the bind pose is used)"];
        if (node.camera >= 0 && (!camera || node.camera < camera->first))
            if (std::optional<ModelCamera> c = place_camera(model, node.camera, in.world, file, diag))
                camera = {node.camera, *c};
        if (const auto it = node.extensions.find(gltf::kLights); it != node.extensions.end() && it->second.IsObject()) {
            const std::optional<int> light =
                it->second.Has("light") ? gltf::value_int(it->second.Get("light"), 0, 1 << 30) : std::nullopt;
            if (!light) throw Error(file, node_name(in.node) + ": " + gltf::kLights + " names no light");
            std::string type;
            if (std::optional<PunctualLight> l = gltf::punctual_light(model, *light, file, type, diag)) {
                switch (transform_light(*l, in.world)) {
                    case LightPlacement::Ok: break;
                    case LightPlacement::NonFinitePosition:
                        throw Error(file, node_name(in.node) + ": its light's position is not finite");
                    case LightPlacement::NonFiniteDirection:
                        throw Error(file, node_name(in.node) + ": its light's direction is not finite");
                }
                lights.push_back(*l);
            } else
                ++skipped[type + " lights"];
        }
        if (node.mesh < 0) continue;
        if (!(std::fabs(determinant3(in.world)) > 0.0f)) continue;  // scaled to nothing: invisible
        const tinygltf::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
        auto& cache = decoded[node.mesh];
        const bool first_use = cache.empty();
        if (first_use) cache.resize(mesh.primitives.size());
        for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
            const tinygltf::Primitive& p = mesh.primitives[i];
            const std::string what = "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(i);
            if (first_use) {
                if (p.mode != TINYGLTF_MODE_TRIANGLES) {
                    ++skipped["primitives of mode " + std::to_string(p.mode) + " (only 4, triangles, is drawn)"];
                    continue;
                }
                if (p.material < -1 || p.material >= int(materials.materials.size()))
                    throw Error(file, what + " names material " + std::to_string(p.material) + ", but the file has " +
                                          std::to_string(materials.materials.size()));
                for (const auto& [name, accessor] : p.attributes)
                    if (name.rfind("TEXCOORD_", 0) == 0 || name.rfind("COLOR_", 0) == 0 ||
                        name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0)
                        if (name != "TEXCOORD_0" && name != "COLOR_0")
                            ++skipped["attribute " + name + " (not used yet)"];
                if (!p.targets.empty()) ++skipped["morph targets"];
                try {
                    const auto draco = p.extensions.find(gltf::kDraco);
                    cache[i] = draco != p.extensions.end() ? gltf::decode_draco(reader, p, draco->second, what)
                                                           : read_primitive(reader, p, what);
                } catch (const gltf::Unsupported& u) {
                    ++skipped[u.feature];
                    continue;
                }
                if (cache[i]->indices.size() % 3 != 0) ++skipped["trailing indices that make no whole triangle"];
                clamped_colors += cache[i]->clamped_colors;
            }
            if (!cache[i]) continue;
            const std::uint32_t material = cache[i]->material < 0 ? kNoMaterial : std::uint32_t(cache[i]->material);
            if (builder.positions.size() + cache[i]->positions.size() >= kNoNormal)
                throw Error(file, "the scene has more than " + std::to_string(kNoNormal - 1) + " vertices");
            append_instance(builder, *cache[i], in.world, material);
            any_triangles = any_triangles || cache[i]->indices.size() >= 3;
        }
    }
    if (!model.animations.empty()) ++skipped["animations (the rest pose is used)"];
    if (!any_triangles) {
        std::string list;
        for (const auto& [what, count] : skipped) list += (list.empty() ? "; skipped " : ", ") + what;
        throw Error(file, "the default scene has no triangles to draw" + list);
    }
    for (const auto& [what, count] : skipped) diag.warn(file, "skipped " + what + " (" + std::to_string(count) + ")");
    if (clamped_colors > 0)
        diag.warn(file, "COLOR_0: " + std::to_string(clamped_colors) + " components outside [0, 1] clamped");

    LoadedMesh out = builder.finish(std::move(materials.materials), diag);
    materials.texture_refs.resize(out.materials.size());  // the default material, if added, has none
    gltf::apply_textures(model, path, materials.texture_refs, out.materials, out.textures, diag);
    out.lights = std::move(lights);
    if (camera) out.camera = camera->second;
    return out;
}

}  // namespace sombra
