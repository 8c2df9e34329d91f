// Test helper: building the small meshes the render tests light and trace,
// and adding them to a scene through its builder, as every scene is made.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "scene/mesh.h"
#include "scene/scene_builder.h"

namespace sombra::testing {

// Appends the triangle (a, b, c), wound a → b → c, with material `material`.
inline void add_triangle(TriangleMesh& mesh, Vec3 a, Vec3 b, Vec3 c, std::uint32_t material) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.material_ids.push_back(material);
}

// Appends the quad (a, b, c, d) as the triangles (a, b, c) and (a, c, d),
// sharing its four corners.
inline void add_quad(TriangleMesh& mesh, Vec3 a, Vec3 b, Vec3 c, Vec3 d, std::uint32_t material) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
    mesh.material_ids.insert(mesh.material_ids.end(), {material, material});
}

// Appends the closed box [lo, hi] (axis-aligned), its faces wound
// counter-clockwise seen from outside.
inline void add_box(TriangleMesh& mesh, Vec3 lo, Vec3 hi, std::uint32_t material) {
    const Vec3 a{lo.x, lo.y, lo.z}, b{hi.x, lo.y, lo.z}, c{hi.x, hi.y, lo.z}, e{lo.x, hi.y, lo.z};
    const Vec3 up{0, 0, hi.z - lo.z};
    add_quad(mesh, a + up, b + up, c + up, e + up, material);  // top, +z
    add_quad(mesh, a, e, c, b, material);                      // bottom, −z
    add_quad(mesh, a, b, b + up, a + up, material);            // −y
    add_quad(mesh, b, c, c + up, b + up, material);            // +x
    add_quad(mesh, c, e, e + up, c + up, material);            // +y
    add_quad(mesh, e, a, a + up, e + up, material);            // −x
}

// Adds `mesh`, in world space as it is, with the materials its
// material_ids index (and the textures their TextureRefs index) to `builder`
// as one object.
inline void add_world_mesh(SceneBuilder& builder, const TriangleMesh& mesh, const std::vector<Material>& materials,
                           const std::vector<Texture>& textures = {}) {
    EXPECT_EQ(builder.add_mesh(mesh, materials, textures, MeshPlacement{"test mesh", "", std::nullopt, std::nullopt}),
              MeshProblem::None);
}

}  // namespace sombra::testing
