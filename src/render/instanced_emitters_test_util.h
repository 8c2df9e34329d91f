// Test helper: one lamp mesh placed twelve times (scaled, rotated, three
// of them mirrored, one of those upside down) above a floor, built twice:
// as instances of the mesh stored once (spec §23) and as flattened copies
// in the world geometry. Light sampling and path tracing must see the two
// as the same lights (render/instanced_lights_test.cpp,
// render/instanced_emitters_path_test.cpp). For tests only.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/test_meshes.h"
#include "scene/scene_builder.h"
#include "scene/transform.h"

namespace sombra::testing {

// The lamp's triangles: a two-sided emitting quad (triangles 0, 1), a
// one-sided emitting triangle facing −y below it (2) and a plain triangle
// standing on it (3), which casts shadows.
inline constexpr std::uint32_t kLampTriangles = 4;

inline std::vector<Material> lamp_materials() {
    Material quad, one_sided, plain;
    quad.kd = one_sided.kd = Vec3{0.0f};
    quad.ke = Vec3{4.0f, 3.0f, 2.0f};
    one_sided.ke = Vec3{1.0f, 2.0f, 6.0f};
    one_sided.emits_front_only = true;
    plain.kd = Vec3{0.4f};
    return {quad, one_sided, plain};
}

inline TriangleMesh lamp_mesh() {
    TriangleMesh mesh;
    add_quad(mesh, {-0.2f, 0, -0.2f}, {-0.2f, 0, 0.2f}, {0.2f, 0, 0.2f}, {0.2f, 0, -0.2f}, 0);
    // (b − a) × (c − a) = (0, −0.04, 0): the front faces down.
    add_triangle(mesh, {0, -0.05f, 0}, {0.2f, -0.05f, 0}, {0, -0.05f, 0.2f}, 1);
    add_triangle(mesh, {-0.1f, 0.01f, 0}, {0.1f, 0.01f, 0}, {0, 0.3f, 0}, 2);
    return mesh;
}

// The twelve placements: lamps between heights 0.9 and 2, none reaching
// the floor's plane; 4, 6 and 10 mirror (6 in y: its one-sided triangle
// faces up).
inline std::vector<Transform> lamp_placements() {
    const auto t = [](float x, float y, float z) { return make_translate({x, y, z}); };
    return {
        t(0, 1.2f, 0),
        compose(make_scale(Vec3{1.5f}), t(1, 1.5f, 0.5f)),
        compose(make_rotate({0, 1, 0}, 30), t(-1, 1, 0.8f)),
        compose(make_scale({-1, 1, 1}), t(0.8f, 1.1f, -0.9f)),
        compose(make_scale({1, 1, -1}), compose(make_rotate({1, 0, 0}, 20), t(-0.7f, 1.4f, -1.2f))),
        compose(make_scale({1, -1, 1}), t(0.3f, 1.6f, 1.3f)),
        compose(make_scale({2, 1, 0.5f}), t(-1.5f, 1.8f, -0.3f)),
        compose(make_rotate({0, 0, 1}, 45), t(1.6f, 1.3f, -1.6f)),
        compose(make_scale(Vec3{0.5f}), t(0, 0.9f, -0.5f)),
        compose(make_rotate({1, 0, 0}, -35), compose(make_scale({-0.8f, 0.8f, 0.8f}), t(-0.3f, 1.25f, 0.4f))),
        t(1.9f, 2.0f, 1.9f),
        compose(make_rotate({1, 1, 0}, 60), t(-1.9f, 1.5f, 1.7f)),
    };
}

// The floor, y = 0, object 0 of both scenes (triangles 0 and 1).
inline void add_floor(SceneBuilder& b) {
    TriangleMesh floor;
    add_quad(floor, {-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, 0);
    Material grey;
    grey.kd = Vec3{0.5f};
    add_world_mesh(b, floor, {grey});
}

// The lamps as instances 0–11 of one mesh.
inline Scene instanced_lamps() {
    SceneBuilder b;
    add_floor(b);
    const std::vector<Transform> placements = lamp_placements();
    EXPECT_EQ(b.add_instanced_mesh(lamp_mesh(), lamp_materials(), {},
                                   MeshPlacement{"/objects/1", "lamp.obj", std::nullopt, std::nullopt}, placements),
              MeshProblem::None);
    return b.finish();
}

// The same lamps copied into the world geometry: lamp k's triangle t is
// world triangle 2 + kLampTriangles·k + t.
inline Scene flattened_lamps() {
    SceneBuilder b;
    add_floor(b);
    const std::vector<Transform> placements = lamp_placements();
    for (std::size_t k = 0; k < placements.size(); ++k)
        EXPECT_EQ(
            b.add_mesh(lamp_mesh(), lamp_materials(), {},
                       MeshPlacement{"/objects/" + std::to_string(k + 1), "lamp.obj", placements[k], std::nullopt}),
            MeshProblem::None);
    return b.finish();
}

inline std::uint32_t flattened_triangle(std::uint32_t instance, std::uint32_t triangle) {
    return 2 + kLampTriangles * instance + triangle;
}

}  // namespace sombra::testing
