// emits_light (spec §27): what counts as a source of light in a scene.
#include <gtest/gtest.h>

#include <vector>

#include "scene/scene.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

// One triangle wearing `material`.
SceneBuilder with_triangle(const Material& material) {
    SceneBuilder b;
    TriangleMesh t;
    t.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    t.triangles = {{0, 1, 2}};
    t.material_ids = {0};
    MeshPlacement placement;
    placement.name = "t";
    EXPECT_EQ(b.add_mesh(t, std::vector<Material>{material}, {}, placement), MeshProblem::None);
    return b;
}

TEST(EmitsLight, NothingButGreySurfacesEmitsNothing) {
    EXPECT_FALSE(emits_light(with_triangle(default_material()).finish()));
    SceneBuilder dark = with_triangle(default_material());
    dark.add_light(make_point_light({0, 1, 0}, Vec3{0.0f}));                                    // a light of no power
    dark.add_material(Material{"lamp", MaterialType::Diffuse, Vec3{0.5f}, {}, 1, Vec3{3.0f}});  // worn by nothing
    EXPECT_FALSE(emits_light(dark.finish()));
}

TEST(EmitsLight, ALightAnEmitterABackgroundAnEnvironmentOrAGlowingMediumDo) {
    SceneBuilder light = with_triangle(default_material());
    light.add_light(make_point_light({0, 1, 0}, Vec3{0.0f, 0.0f, 1.0f}));
    EXPECT_TRUE(emits_light(light.finish()));

    EXPECT_TRUE(
        emits_light(with_triangle(Material{"lamp", MaterialType::Diffuse, Vec3{0.5f}, {}, 1, Vec3{3.0f}}).finish()));

    SceneBuilder sky = with_triangle(default_material());
    sky.set_background({0.0f, 0.1f, 0.0f});
    EXPECT_TRUE(emits_light(sky.finish()));

    EnvironmentMap map;
    map.image.width = 2;
    map.image.height = 1;
    map.image.rgb = {0, 0, 0, 0, 0, 0.5f};
    SceneBuilder lit = with_triangle(default_material());
    lit.set_environment(map);
    EXPECT_TRUE(emits_light(lit.finish()));
    map.scale = 0.0f;  // a map scaled to nothing replaces the background with black
    SceneBuilder unlit = with_triangle(default_material());
    unlit.set_background(Vec3{1.0f});
    unlit.set_environment(map);
    EXPECT_FALSE(emits_light(unlit.finish()));

    Medium glow;
    glow.emission = {0.1f, 0.0f, 0.0f};
    SceneBuilder fog = with_triangle(default_material());
    fog.set_media({glow}, 0);
    EXPECT_TRUE(emits_light(fog.finish()));
}

}  // namespace
}  // namespace sombra
