// glTF files that draw one pyramid several times, for the instancing
// tests (io/gltf/gltf_instancing_test.cpp, render/gltf_instancing_render_test.cpp):
// each as instances and as the same placements with copies of the mesh.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "io/gltf/gltf_test_files.h"

namespace sombra::gltf_test {

inline constexpr int kInstances = 5;

namespace instancing {

// Three placements of one pyramid: shifted, rotated, mirrored in x.
inline const nlohmann::json kPlacements[3] = {{{"translation", {-2.5, 0, 0}}},
                                              {{"rotation", {0, 0.3826834, 0, 0.9238795}}},  // 45° about +y
                                              {{"translation", {2.5, 0, 0}}, {"scale", {-1, 1, 1}}}};

inline GltfFile shared_mesh_file() {
    GltfFile f;
    add_pyramid(f);
    for (nlohmann::json node : kPlacements) {
        node["mesh"] = 0;
        f.add_node(node);
    }
    f.set_scene({0, 1, 2});
    return f;
}
inline GltfFile copied_mesh_file() {
    GltfFile f;
    for (nlohmann::json node : kPlacements) {
        node["mesh"] = add_pyramid(f);
        f.add_node(node);
    }
    f.set_scene({0, 1, 2});
    return f;
}

// Five instances as EXT_mesh_gpu_instancing gives them (ROTATION as
// normalised shorts when `quantized_rotation`), on a node that is itself
// moved, against the same placements written as nodes with their own copies.
struct Trs {
    Vec3 t;
    float q[4];
    Vec3 s;
};
inline Trs instance_trs(int k) {
    const double half = 0.2 * k;  // rotations about (1, 1, 0)/√2
    const auto c = float(std::cos(half)), s = float(std::sin(half) / std::sqrt(2.0));
    return {{1.5f * float(k), 0.2f * float(k), 0}, {s, s, 0, c}, {1 + 0.1f * float(k), 1, k == 3 ? -1.0f : 1.0f}};
}
inline const nlohmann::json kNodeMove = {{"translation", {0, 0, -1}}, {"scale", {1, 2, 1}}};

inline GltfFile gpu_instanced_file(bool quantized_rotation = false) {
    GltfFile f;
    add_pyramid(f);
    std::vector<Vec3> t, s;
    std::vector<float> q;
    std::vector<std::int16_t> q16;
    for (int k = 0; k < kInstances; ++k) {
        const Trs trs = instance_trs(k);
        t.push_back(trs.t);
        s.push_back(trs.s);
        for (const float x : trs.q) {
            q.push_back(x);
            q16.push_back(static_cast<std::int16_t>(std::lround(x * 32767)));
        }
    }
    const int rotation = quantized_rotation ? f.add_array(q16, kShort, kInstances, "VEC4", true)
                                            : f.add_array(q, kFloat, kInstances, "VEC4");
    nlohmann::json node = kNodeMove;
    node["mesh"] = 0;
    node["extensions"] = {{"EXT_mesh_gpu_instancing",
                           {{"attributes",
                             {{"TRANSLATION", f.add_array(t, kFloat, kInstances, "VEC3")},
                              {"ROTATION", rotation},
                              {"SCALE", f.add_array(s, kFloat, kInstances, "VEC3")}}}}}};
    f.add_node(node);
    f.set_scene({0});
    f.use_extension("EXT_mesh_gpu_instancing", true);
    return f;
}
// Each instance as a child node of the moved node, with a copy of the mesh.
inline GltfFile gpu_copies_file() {
    GltfFile f;
    nlohmann::json parent = kNodeMove;
    parent["children"] = nlohmann::json::array();
    f.add_node(parent);
    for (int k = 0; k < kInstances; ++k) {
        const Trs trs = instance_trs(k);
        f.doc["nodes"][0]["children"].push_back(k + 1);
        f.add_node({{"mesh", add_pyramid(f)},
                    {"translation", {trs.t.x, trs.t.y, trs.t.z}},
                    {"rotation", {trs.q[0], trs.q[1], trs.q[2], trs.q[3]}},
                    {"scale", {trs.s.x, trs.s.y, trs.s.z}}});
    }
    f.set_scene({0});
    return f;
}

}  // namespace instancing

}  // namespace sombra::gltf_test
