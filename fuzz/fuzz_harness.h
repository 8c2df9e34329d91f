// What each fuzz target does with one input, shared with the regression test
// (src/io/fuzz_regression_test.cpp) so that a reproducer replays exactly as
// the fuzzer ran it: the bytes become files in a scratch folder, the loader
// reads them by path, and the result is checked against the invariants the
// renderer relies on. A sombra::Error is the expected outcome for a bad input;
// anything else escaping is a bug.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/image_limits.h"
#include "io/images/texture_image.h"
#include "io/mesh_file.h"
#include "io/scene_json/scene_file.h"
#include "io/vdb/vdb_reader.h"
#include "scene/scene.h"
#include "scene/texture.h"
#include "scene/transform.h"

namespace sombra::fuzz {

namespace fs = std::filesystem;

// fuzz_obj's input is OBJ text, optionally followed by this line and the text
// of the MTL file "m.mtl" beside it (reached through "mtllib m.mtl").
inline constexpr std::string_view kMtlSeparator = "\n#MTL\n";
inline constexpr const char* kMtlName = "m.mtl";

enum class Target { Obj, Ply, Scene, Gltf, Texture, Vdb };

// A 2×2 RGB PNG (red, green over blue, white) for the scenes and MTL
// materials of fuzz_scene to name as "t.png".
inline constexpr std::string_view kTexturePng{
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x02\x00\x00\x00\x02\x08\x02\x00"
    "\x00\x00\xfd\xd4\x9a\x73\x00\x00\x00\x12\x49\x44\x41\x54\x78\xda\x63\xf8\xcf\xc0\xc0\x00\xc2\x0c\xff\x81\x00"
    "\x00\x1f\xee\x05\xfb\xf1\xab\xba\x77\x00\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82",
    75};

// fuzz_texture's input is an image file: written as fuzz.hdr when it starts
// "#?" (Radiance), as fuzz.exr when it starts with OpenEXR's magic number,
// else as fuzz.png (PNG, JPEG, TGA and BMP are told apart by content).
inline std::string texture_file_name(std::string_view bytes) {
    if (bytes.starts_with("#?")) return "fuzz.hdr";
    if (bytes.starts_with("\x76\x2f\x31\x01")) return "fuzz.exr";
    return "fuzz.png";
}
// ... and decoded as colour when its size is even, as data when odd.
inline TextureEncoding texture_encoding(std::string_view bytes) {
    return bytes.size() % 2 == 0 ? TextureEncoding::Color : TextureEncoding::Data;
}

inline void write_file(const fs::path& path, std::string_view bytes) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) throw std::runtime_error("fuzz harness: cannot write " + path.string());
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    if (std::fclose(file) != 0 || !ok) throw std::runtime_error("fuzz harness: cannot write " + path.string());
}

// The meshes fuzz_scene's objects can name ("file": "m.obj" or "m.ply"):
// a quad with a normal, texture coordinates and an MTL material, and a PLY
// triangle; and the texture t.png that materials can name.
inline void write_scene_meshes(const fs::path& folder) {
    write_file(folder / "m.obj",
               "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
               "usemtl red\nf 1/1/1 2/2/1 3/3/1 4/4/1\n");
    write_file(folder / "m.mtl", "newmtl red\nKd 0.8 0.1 0.1\nKs 0.1 0.1 0.1\nNs 10\nKe 0 0 0\nmap_Kd t.png\n");
    write_file(folder / "t.png", kTexturePng);
    write_file(folder / "m.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
}

// Writes one input's files into `folder` and returns the file to load.
inline fs::path stage_input(Target target, std::string_view bytes, const fs::path& folder) {
    switch (target) {
        case Target::Obj: {
            const std::size_t split = bytes.find(kMtlSeparator);
            write_file(folder / "fuzz.obj", bytes.substr(0, split));
            std::error_code ec;
            fs::remove(folder / kMtlName, ec);
            if (split != std::string_view::npos)
                write_file(folder / kMtlName, bytes.substr(split + kMtlSeparator.size()));
            return folder / "fuzz.obj";
        }
        case Target::Ply: write_file(folder / "fuzz.ply", bytes); return folder / "fuzz.ply";
        case Target::Gltf: {
            // The container decides the name: GLB bytes start with "glTF".
            const fs::path path = folder / (bytes.substr(0, 4) == "glTF" ? "fuzz.glb" : "fuzz.gltf");
            write_file(path, bytes);
            return path;
        }
        case Target::Scene:
            if (!fs::exists(folder / "t.png")) write_scene_meshes(folder);
            write_file(folder / "scene.json", bytes);
            return folder / "scene.json";
        case Target::Texture: {
            const fs::path path = folder / texture_file_name(bytes);
            write_file(path, bytes);
            return path;
        }
        case Target::Vdb: write_file(folder / "fuzz.vdb", bytes); return folder / "fuzz.vdb";
    }
    return {};
}

// "" when `g` is a density the renderer can track through, else what is wrong.
inline std::string density_problem(const DensityGrid& g) {
    std::uint64_t voxels = 1;
    for (const int d : g.dims) {
        if (d < 2) return "a dense box thinner than its padding";
        voxels *= static_cast<std::uint64_t>(d);
    }
    if (voxels > kMaxDenseVoxels || g.values.size() != voxels) return "dense box and values differ";
    float largest = 0;
    for (const float v : g.values) {
        if (!std::isfinite(v) || v < 0) return "a density not finite or negative";
        largest = std::max(largest, v);
    }
    if (largest != g.max_value) return "max_value is not the largest density";
    std::uint64_t cells = 1;
    for (const int c : g.cells) cells *= static_cast<std::uint64_t>(c);
    if (g.majorants.size() != cells) return "majorant grid of the wrong size";
    for (const float v : g.index_to_world.m)
        if (!std::isfinite(v)) return "non-finite transform";
    return {};
}

inline bool in_unit_range(Vec3 c) { return min_component(c) >= 0 && max_component(c) <= 1; }

// "" when `m` is usable by the renderer with `materials`, else what is wrong.
inline std::string mesh_problem(const TriangleMesh& m, std::size_t material_count) {
    if (m.triangles.empty()) return "no triangles";
    for (const Vec3& p : m.positions)
        if (!is_finite(p)) return "non-finite position";
    for (const Index3& t : m.triangles)
        for (std::uint32_t i : t)
            if (i >= m.positions.size()) return "triangle index out of range";
    if (m.material_ids.size() != m.triangles.size()) return "material_ids and triangles differ in size";
    for (std::uint32_t id : m.material_ids)
        if (id >= material_count) return "material id out of range";
    if (!m.normal_indices.empty() && m.normal_indices.size() != m.triangles.size())
        return "normal_indices and triangles differ in size";
    if (m.normal_indices.empty() && !m.normals.empty()) return "normals without normal_indices";
    for (const Index3& t : m.normal_indices)
        for (std::uint32_t i : t)
            if (i != kNoNormal && i >= m.normals.size()) return "normal index out of range";
    for (const Vec3& n : m.normals)
        if (!is_finite(n) || std::fabs(length(n) - 1) > 1e-3f) return "normal not of unit length";
    // uvs, tangents and colours follow the normals' convention.
    const auto corners_problem = [&](const std::vector<Index3>& indices, std::size_t values, std::uint32_t none,
                                     const char* name) -> std::string {
        if (!indices.empty() && indices.size() != m.triangles.size())
            return std::string(name) + " indices and triangles differ in size";
        if (indices.empty() && values != 0) return std::string(name) + " without indices";
        for (const Index3& t : indices)
            for (std::uint32_t i : t)
                if (i != none && i >= values) return std::string(name) + " index out of range";
        return {};
    };
    if (std::string p = corners_problem(m.uv_indices, m.uvs.size(), kNoUv, "uv"); !p.empty()) return p;
    if (std::string p = corners_problem(m.tangent_indices, m.tangents.size(), kNoTangent, "tangent"); !p.empty())
        return p;
    if (std::string p = corners_problem(m.color_indices, m.colors.size(), kNoColor, "colour"); !p.empty()) return p;
    for (const VertexTangent& t : m.tangents)
        if (!is_finite(t.direction) || std::fabs(length(t.direction) - 1) > 1e-3f ||
            (t.handedness != 1.0f && t.handedness != -1.0f))
            return "tangent not of unit length or handedness not ±1";
    for (const Rgba& c : m.colors)
        for (float x : c)
            if (!(x >= 0.0f && x <= 1.0f)) return "colour outside [0, 1]";
    return {};
}

inline std::string material_problem(const Material& m) {
    if (!in_unit_range(m.kd) || !in_unit_range(m.ks)) return "material '" + m.name + "': kd or ks outside [0, 1]";
    if (!is_finite(m.ke) || min_component(m.ke) < 0) return "material '" + m.name + "': ke not finite and >= 0";
    if (!std::isfinite(m.shininess) || m.shininess < 0) return "material '" + m.name + "': bad shininess";
    if (!in_unit_range(m.kr) || !in_unit_range(m.kt)) return "material '" + m.name + "': kr or kt outside [0, 1]";
    // A dielectric refracts (ior > 1); pbr's ior only sets f0, and glTF's 1 is valid.
    const bool ior_ok = m.type == MaterialType::Pbr ? m.ior >= 1 || m.ior == 0 : m.ior > 1;
    if (!ior_ok || !std::isfinite(m.ior))
        return "material '" + m.name + "': ior not finite and > 1 (>= 1 or 0 for pbr)";
    if (!(m.roughness >= 0 && m.roughness <= 1)) return "material '" + m.name + "': roughness outside [0, 1]";
    if (!in_unit_range(m.base_color) || !(m.metallic >= 0 && m.metallic <= 1))
        return "material '" + m.name + "': base_color or metallic outside [0, 1]";
    return {};
}

// "" when the texture is usable: a size within the limits, every texel
// finite and >= 0, and <= 1 when `unit` (8- and 16-bit images).
inline std::string texture_problem(const Texture& t, bool unit) {
    if (t.width < 1 || t.height < 1 || t.width > kMaxImageSide || t.height > kMaxImageSide) return "bad texture size";
    if (t.channels < 1 || t.channels > 4) return "bad texture channel count";
    const auto values = static_cast<std::int64_t>(t.width) * t.height * t.channels;
    if (values > kMaxTextureValues || t.texels.size() != static_cast<std::size_t>(values)) return "bad texel count";
    for (float v : t.texels)
        if (!std::isfinite(v) || v < 0 || (unit && v > 1)) return "texel out of range";
    return {};
}

// "" when every texture reference of the materials is in range and each
// texture usable.
inline std::string textures_problem(const std::vector<Material>& materials, const std::vector<Texture>& textures) {
    for (const Texture& t : textures)
        if (std::string problem = texture_problem(t, false); !problem.empty()) return problem;
    for (Material m : materials) {
        std::string problem;
        for_each_texture_ref(m.textures, [&](TextureRef& r) {
            if (r.is_set() && (r.texture >= textures.size() || r.channel > 3))
                problem = "texture reference out of range";
        });
        if (!problem.empty()) return "material '" + m.name + "': " + problem;
        if (m.textured != any_texture(m.textures)) return "material '" + m.name + "': textured flag wrong";
        if (!std::isfinite(m.textures.bump_scale) || !(m.textures.alpha_cutoff >= 0 && m.textures.alpha_cutoff <= 1))
            return "material '" + m.name + "': bad bump scale or alpha cutoff";
        if (!std::isfinite(m.textures.normal_scale)) return "material '" + m.name + "': normal scale not finite";
        for_each_texture_ref(m.textures, [&](TextureRef& r) {
            const UvTransform& u = r.uv_transform;
            for (float x : {u.uu, u.uv, u.u0, u.vu, u.vv, u.v0})
                if (!std::isfinite(x)) problem = "uv transform not finite";
        });
        if (!problem.empty()) return "material '" + m.name + "': " + problem;
    }
    return {};
}

// Why a light is unusable, or "": finite values, non-negative intensity, a
// unit direction for spots and directional lights, spot cosines in order.
inline std::string light_problem(const PunctualLight& light) {
    if (!is_finite(light.position) || !is_finite(light.intensity) || min_component(light.intensity) < 0)
        return "bad light";
    if (light.type != LightType::Point && !(std::fabs(length(light.direction) - 1) < 1e-3f))
        return "light direction not unit";
    if (light.type == LightType::Spot && !(light.cos_outer >= -1e-6f && light.cos_outer < 1 &&
                                           light.cos_inner >= light.cos_outer && light.cos_inner <= 1))
        return "bad spot cone";
    return {};
}

// "" when an instance transform is usable: finite and invertible.
inline std::string instance_transform_problem(const Transform& t) {
    for (const float x : t.m)
        if (!std::isfinite(x)) return "non-finite instance transform";
    const float det = determinant3(t);
    if (!(det != 0.0f) || !std::isfinite(det)) return "singular instance transform";
    return {};
}

// "" when a mesh file's instanced parts are usable: each a mesh as good as
// the flattened one, drawn at least twice (once if animated), its origins
// covering its instances.
inline std::string parts_problem(const LoadedMesh& loaded) {
    for (const InstancedPart& part : loaded.instanced) {
        if (std::string problem = mesh_problem(part.mesh, loaded.materials.size()); !problem.empty())
            return "instanced part: " + problem;
        // A part a glTF animation moves may be drawn once (spec §22).
        if (part.instances.size() < (part.nodes.empty() ? 2u : 1u)) return "an instanced part drawn fewer than twice";
        if (!part.nodes.empty() && (!loaded.animation || part.nodes.size() != part.instances.size() ||
                                    part.local.size() != part.instances.size()))
            return "an animated part without one node per instance";
        for (const std::uint32_t n : part.nodes)
            if (n >= loaded.animation->nodes.size()) return "an animated part's node out of range";
        // Evaluated before, inside and after the keys, for the sanitizers (a
        // singular moment is the renderer's error to report, not a bug).
        if (&part == &loaded.instanced.front() && !part.nodes.empty())
            for (const double t : {-1.0, 0.5 * loaded.animation->end_time, loaded.animation->end_time + 1})
                if (gltf_node_worlds(*loaded.animation, t).size() != loaded.animation->nodes.size())
                    return "node transforms missing";
        if (part.origins.empty() || part.origins[0].first != 0) return "instances without an origin";
        for (const Transform& t : part.instances)
            if (std::string problem = instance_transform_problem(t); !problem.empty()) return problem;
    }
    return {};
}

inline std::string loaded_mesh_problem(const LoadedMesh& loaded) {
    for (const Material& m : loaded.materials)
        if (std::string problem = material_problem(m); !problem.empty()) return problem;
    for (const PunctualLight& light : loaded.lights)
        if (std::string problem = light_problem(light); !problem.empty()) return problem;
    if (const std::optional<ModelCamera>& c = loaded.camera;
        c && !(is_finite(c->origin) && is_finite(c->forward) && is_finite(c->up) && c->yfov_degrees > 0 &&
               c->yfov_degrees < 180 && std::isfinite(c->aspect) && c->aspect >= 0 &&
               std::fabs(length(c->forward) - 1) < 1e-3f && std::fabs(length(c->up) - 1) < 1e-3f))
        return "bad camera";
    if (std::string problem = textures_problem(loaded.materials, loaded.textures); !problem.empty()) return problem;
    if (std::string problem = parts_problem(loaded); !problem.empty()) return problem;
    // Everything may be instanced: the flattened mesh is then empty.
    if (loaded.mesh.triangles.empty() && !loaded.instanced.empty()) return {};
    return mesh_problem(loaded.mesh, loaded.materials.size());
}

inline std::string scene_problem(const LoadedScene& loaded) {
    if (std::string problem = render_settings_problem(loaded.settings); !problem.empty()) return problem;
    const Scene& scene = loaded.scene;
    if (!is_finite(scene.background) || min_component(scene.background) < 0) return "bad background";
    const CameraSpec& c = scene.camera;
    if (c.basis.has_value() == c.look_at.has_value()) return "not exactly one camera form";
    if (c.basis && !(is_finite(c.basis->origin) && is_finite(c.basis->left) && is_finite(c.basis->up) &&
                     is_finite(c.basis->forward)))
        return "non-finite camera basis";
    if (c.look_at && !(is_finite(c.look_at->origin) && is_finite(c.look_at->look_at) && is_finite(c.look_at->up) &&
                       c.look_at->fov_degrees > 0 && c.look_at->fov_degrees < 180))
        return "bad look-at camera";
    for (const PunctualLight& light : scene.lights)
        if (std::string problem = light_problem(light); !problem.empty()) return problem;
    if (!(c.aperture_radius >= 0 && std::isfinite(c.aperture_radius))) return "bad aperture";
    if (c.focus_distance && !(*c.focus_distance > 0 && std::isfinite(*c.focus_distance))) return "bad focus distance";
    for (const Material& m : scene.materials)
        if (std::string problem = material_problem(m); !problem.empty()) return problem;
    if (std::string problem = textures_problem(scene.materials, scene.textures); !problem.empty()) return problem;
    for (const TriangleMesh& mesh : scene.instanced_meshes)
        if (std::string problem = mesh_problem(mesh, scene.materials.size()); !problem.empty())
            return "instanced mesh: " + problem;
    for (const Instance& instance : scene.instances) {
        if (instance.mesh >= scene.instanced_meshes.size() || instance.object >= scene.objects.size())
            return "instance index out of range";
        if (std::string problem = instance_transform_problem(instance.object_to_world); !problem.empty())
            return problem;
    }
    // Everything may be instanced (spec §23): the world geometry is then empty.
    if (scene.geometry.triangles.empty() && !scene.instances.empty()) return {};
    return mesh_problem(scene.geometry, scene.materials.size());
}

// Loads one input as the fuzz target for `target` does. Returns "" when it
// loaded and passed every check, or when the loader threw sombra::Error (the
// right answer to a bad input); otherwise what is wrong with the result.
// Any other exception propagates: that is a bug too.
inline std::string run_input(Target target, std::string_view bytes, const fs::path& folder) {
    const fs::path path = stage_input(target, bytes, folder);
    Diagnostics diag;
    try {
        switch (target) {
            case Target::Obj: return loaded_mesh_problem(load_obj(path, diag));
            case Target::Ply: return loaded_mesh_problem(load_ply(path, diag));
            case Target::Scene: return scene_problem(load_scene_file(path, diag));
            case Target::Gltf: return loaded_mesh_problem(load_gltf(path, diag));
            case Target::Texture: {
                const bool deep = path.extension() != ".png";  // EXR and HDR values may exceed 1
                return texture_problem(read_texture_file(path, texture_encoding(bytes)), !deep);
            }
            case Target::Vdb: return density_problem(read_vdb_density(path, "density"));
        }
    } catch (const Error&) {
        return {};
    }
    return {};
}

}  // namespace sombra::fuzz
