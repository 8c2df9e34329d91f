// Materials of scene files (spec §5, §11): mirror, dielectric, conductor
// and pbr as read, and the warning for a phong material that gains energy.
#include <gtest/gtest.h>

#include <string>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

class SceneMaterials : public testing::SceneFileTest {};

TEST_F(SceneMaterials, MirrorDielectricAndConductorMaterialsAreRead) {
    const Scene s = load(scene(R"("materials": {
        "mirror": {"type": "mirror", "kr": [0.9, 0.8, 0.7], "ke": [1, 0, 0]},
        "glass": {"type": "dielectric"},
        "water": {"type": "dielectric", "ior": 1.33, "kt": [0.5, 1, 1]},
        "gold": {"type": "conductor", "ks": [1, 0.78, 0.34], "roughness": 0.25}})"));
    ASSERT_EQ(s.materials.size(), 5u);  // in name order, then tri.obj's default
    const Material& glass = s.materials[0];
    EXPECT_EQ(glass.type, MaterialType::Dielectric);
    EXPECT_EQ(glass.ior, 1.5f);
    EXPECT_EQ(glass.kt, Vec3{1.0f});
    const Material& gold = s.materials[1];
    EXPECT_EQ(gold.type, MaterialType::Conductor);
    EXPECT_EQ(gold.ks, (Vec3{1, 0.78f, 0.34f}));
    EXPECT_EQ(gold.roughness, 0.25f);
    const Material& mirror = s.materials[2];
    EXPECT_EQ(mirror.type, MaterialType::Mirror);
    EXPECT_EQ(mirror.kr, (Vec3{0.9f, 0.8f, 0.7f}));
    EXPECT_EQ(mirror.ke, (Vec3{1, 0, 0}));
    const Material& water = s.materials[3];
    EXPECT_EQ(water.ior, 1.33f);
    EXPECT_EQ(water.kt, (Vec3{0.5f, 1, 1}));
}

TEST_F(SceneMaterials, PbrMaterialIsRead) {
    const Scene s = load(scene(R"("materials": {
        "plastic": {"type": "pbr", "base_color": [0.8, 0.1, 0.1], "metallic": 0, "roughness": 0.3},
        "steel": {"type": "pbr", "base_color": [0.6, 0.6, 0.65], "metallic": 1, "roughness": 0.5, "ior": 2.5,
                  "ke": [0.1, 0, 0]}})"));
    ASSERT_EQ(s.materials.size(), 3u);  // in name order, then tri.obj's default
    const Material& plastic = s.materials[0];
    EXPECT_EQ(plastic.name, "plastic");
    EXPECT_EQ(plastic.type, MaterialType::Pbr);
    EXPECT_EQ(plastic.base_color, (Vec3{0.8f, 0.1f, 0.1f}));
    EXPECT_EQ(plastic.metallic, 0.0f);
    EXPECT_EQ(plastic.roughness, 0.3f);
    EXPECT_EQ(plastic.ior, 1.5f);  // the default
    EXPECT_EQ(plastic.ke, Vec3{0.0f});
    const Material& steel = s.materials[1];
    EXPECT_EQ(steel.type, MaterialType::Pbr);
    EXPECT_EQ(steel.metallic, 1.0f);
    EXPECT_EQ(steel.roughness, 0.5f);
    EXPECT_EQ(steel.ior, 2.5f);
    EXPECT_EQ(steel.ke, (Vec3{0.1f, 0, 0}));
    EXPECT_TRUE(diag.warnings.empty());
    // The ends of the ranges are allowed, and a pbr material does not ask for the path integrator.
    const Scene ends =
        load(with_material(R"({"type": "pbr", "base_color": [0, 0, 1], "metallic": 1, "roughness": 0})"));
    EXPECT_EQ(ends.materials[0].roughness, 0.0f);
    EXPECT_FALSE(needs_path_integrator(ends));
}

TEST_F(SceneMaterials, EnergyGainWarns) {
    load(scene(
        R"("materials": {"hot": {"type": "phong", "kd": [0.7, 0.5, 0.5], "ks": [0.4, 0.5, 0.5], "shininess": 10}})"));
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("/materials/hot"), std::string::npos) << diag.warnings[0];
}

}  // namespace
}  // namespace sombra
