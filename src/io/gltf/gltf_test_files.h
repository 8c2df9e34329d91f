// Tiny glTF files written by the tests (scene and command-line tests): a
// JSON document built with nlohmann-json and one binary buffer, saved as
// .gltf (the buffer as a base64 data URI) or .glb.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/base64.h"
#include "core/vec2.h"
#include "core/vec3.h"

namespace sombra::gltf_test {

inline constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
                     kFloat = 5126;

struct GltfFile {
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
    std::string bin;

    // Appends raw bytes (4-byte aligned) as a new buffer view; returns its index.
    int add_view(const void* data, std::size_t size, std::size_t stride = 0) {
        while (bin.size() % 4 != 0) bin.push_back('\0');
        nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
        if (stride) view["byteStride"] = stride;
        bin.append(static_cast<const char*>(data), size);
        doc["bufferViews"].push_back(view);
        return int(doc["bufferViews"].size()) - 1;
    }
    // An accessor over view `view`; returns its index.
    int add_accessor(int view, int component_type, std::size_t count, const char* type, bool normalized = false,
                     std::size_t byte_offset = 0) {
        nlohmann::json a = {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
        if (normalized) a["normalized"] = true;
        if (byte_offset) a["byteOffset"] = byte_offset;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size()) - 1;
    }
    template <class T>
    int add_array(const std::vector<T>& values, int component_type, std::size_t count, const char* type,
                  bool normalized = false) {
        return add_accessor(add_view(values.data(), values.size() * sizeof(T)), component_type, count, type,
                            normalized);
    }
    int add_positions(const std::vector<Vec3>& p) { return add_array(p, kFloat, p.size(), "VEC3"); }
    int add_normals(const std::vector<Vec3>& n) { return add_array(n, kFloat, n.size(), "VEC3"); }
    int add_uvs(const std::vector<Vec2>& uv) { return add_array(uv, kFloat, uv.size(), "VEC2"); }
    int add_indices(const std::vector<std::uint32_t>& i) { return add_array(i, kUnsignedInt, i.size(), "SCALAR"); }

    // A mesh of one triangle primitive; returns its index.
    int add_mesh(nlohmann::json attributes, int indices = -1, int material = -1) {
        nlohmann::json p = {{"attributes", attributes}};
        if (indices >= 0) p["indices"] = indices;
        if (material >= 0) p["material"] = material;
        doc["meshes"].push_back({{"primitives", {p}}});
        return int(doc["meshes"].size()) - 1;
    }
    int add_node(nlohmann::json node) {
        doc["nodes"].push_back(std::move(node));
        return int(doc["nodes"].size()) - 1;
    }
    // The default scene with these root nodes.
    void set_scene(std::vector<int> roots) {
        doc["scenes"] = nlohmann::json::array({{{"nodes", roots}}});
        doc["scene"] = 0;
    }
    void use_extension(const std::string& name, bool required = false) {
        doc["extensionsUsed"].push_back(name);
        if (required) doc["extensionsRequired"].push_back(name);
    }

    std::string gltf() const {
        nlohmann::json d = doc;
        if (!bin.empty() && !d.contains("buffers"))  // a test may have written its own
            d["buffers"] = {
                {{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64_encode(bin)}}};
        return d.dump();
    }
    std::string glb() const {
        nlohmann::json d = doc;
        std::string body = bin;
        while (body.size() % 4 != 0) body.push_back('\0');
        if (!bin.empty() && !d.contains("buffers")) d["buffers"] = {{{"byteLength", bin.size()}}};
        std::string json = d.dump();
        while (json.size() % 4 != 0) json.push_back(' ');
        std::string out;
        const auto u32 = [&out](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
        u32(0x46546C67);
        u32(2);
        u32(std::uint32_t(12 + 8 + json.size() + (body.empty() ? 0 : 8 + body.size())));
        u32(std::uint32_t(json.size()));
        u32(0x4E4F534A);
        out += json;
        if (!body.empty()) {
            u32(std::uint32_t(body.size()));
            u32(0x004E4942);
            out += body;
        }
        return out;
    }
    // Writes .gltf or .glb by the path's extension.
    void save(const std::filesystem::path& path) const {
        std::ofstream(path, std::ios::binary) << (path.extension() == ".glb" ? glb() : gltf());
    }
};

// A unit quad in z = 0 facing +z, corners counter-clockwise, as a glTF with
// one mesh (indexed, with normals and uvs) and no nodes yet.
inline GltfFile quad_file(bool indexed = true) {
    GltfFile f;
    const std::vector<Vec3> corners{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<std::uint32_t> indices{0, 1, 2, 0, 2, 3};
    if (indexed) {
        const int p = f.add_positions(corners);
        const int n = f.add_normals(std::vector<Vec3>(4, Vec3{0, 0, 1}));
        const int uv = f.add_uvs({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
        f.add_mesh({{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", uv}}, f.add_indices(indices));
    } else {
        std::vector<Vec3> unrolled;
        for (std::uint32_t i : indices) unrolled.push_back(corners[i]);
        f.add_mesh({{"POSITION", f.add_positions(unrolled)}});
    }
    return f;
}

// A pyramid (four slanted faces on a square base, apex up +y and off
// centre, so that a mirror shows) added to `f` as one mesh, with vertex
// normals pointing away from its centre so that a wrong normal transform
// shows; returns the mesh's index.
inline int add_pyramid(GltfFile& f, int material = -1) {
    const std::vector<Vec3> p{{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {0.5f, 1.5f, 0.3f}};
    std::vector<Vec3> n;
    for (const Vec3 v : p) n.push_back(normalize(v - Vec3{0, 0.5f, 0}));
    const std::vector<std::uint32_t> i{0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 0, 2, 1, 0, 3, 2};
    return f.add_mesh({{"POSITION", f.add_positions(p)}, {"NORMAL", f.add_normals(n)}}, f.add_indices(i), material);
}

}  // namespace sombra::gltf_test
