// A scene file's "media", the render's and the camera's medium and the
// objects that bound media (spec §26): the values read, scaled, every bad
// value refused in one line naming its key, and the warnings.
#include <gtest/gtest.h>

#include <string>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

class SceneMedia : public testing::SceneFileTest {
protected:
    // A scene whose "media" holds `media` and whose render section is `render`.
    static std::string with_media(const std::string& media, const std::string& render = "{}") {
        return scene(R"("media": )" + media + R"(, "render": )" + render);
    }
    void expect_error(const std::string& text, const std::string& where, const std::string& what) {
        try {
            load(text);
            ADD_FAILURE() << "no error for " << text;
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), scene_path.string() + where) << text;
            EXPECT_NE(e.message().find(what), std::string::npos) << e.message();
        }
    }
    // A closed cube of side 1 (12 triangles) and the same cube without its top.
    static void write_cubes() {
        const std::string corners = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n";
        const std::string sides =
            "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
        write(dir / "cube.obj", corners + sides + "f 3 7 4\nf 4 7 8\n");
        write(dir / "open_cube.obj", corners + sides);
    }
};

TEST_F(SceneMedia, ReadsAHomogeneousMediumAndTheRendersMedium) {
    const Scene s = load(with_media(
        R"({"fog": {"type": "homogeneous", "sigma_a": [0.1, 0.2, 0.3], "sigma_s": [1, 2, 3], "g": 0.5,
                    "emission": [0.01, 0, 0], "scale": 2},
            "air": {"type": "homogeneous"}})",
        R"({"medium": "fog", "integrator": "path", "max_volume_depth": 7})"));
    ASSERT_EQ(s.media.size(), 2u);
    ASSERT_NE(s.render_medium, kNoMedium);
    const Medium& fog = s.media[s.render_medium];
    EXPECT_EQ(fog.name, "fog");
    EXPECT_FLOAT_EQ(fog.sigma_a.y, 0.4f);  // scaled
    EXPECT_FLOAT_EQ(fog.sigma_s.z, 6.0f);
    EXPECT_FLOAT_EQ(fog.g, 0.5f);
    EXPECT_FLOAT_EQ(fog.emission.x, 0.01f);  // emission is not scaled (spec §26)
    EXPECT_FLOAT_EQ(extinction(fog).x, 2.2f);
    const Medium& air = s.media[s.render_medium == 0 ? 1 : 0];
    EXPECT_EQ(air.name, "air");
    EXPECT_EQ(max_component(extinction(air)), 0.0f);
    EXPECT_EQ(
        settings_of(with_media(R"({"fog": {"type": "homogeneous"}})", R"({"max_volume_depth": 7})")).max_volume_depth,
        7);
}

TEST_F(SceneMedia, WithoutMediaTheSceneIsInVacuum) {
    const Scene s = load(scene(""));
    EXPECT_TRUE(s.media.empty());
    EXPECT_EQ(s.render_medium, kNoMedium);
    EXPECT_EQ(settings_of(scene("")).max_volume_depth, 256);
}

TEST_F(SceneMedia, BadValuesNameTheirKey) {
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "sigma_a": [-1, 0, 0]}})"), ": /media/fog/sigma_a",
                 "non-negative");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "sigma_s": [0, 0]}})"), ": /media/fog/sigma_s", "3");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "g": 1}})"), ": /media/fog/g", "between -1 and 1");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "g": -1.5}})"), ": /media/fog/g", "between -1 and 1");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "scale": -2}})"), ": /media/fog/scale", "non-negative");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "sigma_s": [10, 10, 10], "scale": 1e38}})"),
                 ": /media/fog/scale", "overflow");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "colour": [1, 1, 1]}})"), ": /media/fog/colour",
                 "unknown key 'colour'");
    expect_error(with_media(R"({"fog": {"sigma_s": [1, 1, 1]}})"), ": /media/fog/type", "missing required key");
    expect_error(with_media(R"({"fog": {"type": "smoke"}})"), ": /media/fog/type",
                 "unknown medium type 'smoke' (expected 'homogeneous' or 'grid')");
    expect_error(with_media(R"({"fog": {"type": "grid", "file": "smoke.vdb", "emission": [1, 1, 1]}})"),
                 ": /media/fog/emission", "grid media emit nothing");
    expect_error(with_media(R"({"fog": {"type": "grid", "file": "smoke.vdb"}})"), ": /media/fog/file",
                 "'smoke.vdb': cannot open OpenVDB file: no such file");
    expect_error(with_media(R"([1, 2])"), ": /media", "expected an object");
    expect_error(with_media(R"({"fog": {"type": "homogeneous"}})", R"({"medium": "smoke"})"), ": /render/medium",
                 "no medium 'smoke' in /media");
    expect_error(scene(R"("render": {"medium": "fog"})"), ": /render/medium", "no medium 'fog' in /media");
    expect_error(scene(R"("render": {"max_volume_depth": -1})"), ": /render/max_volume_depth", "between 0 and 65536");
}

constexpr const char* kTwoMedia = R"("media": {"smoke": {"type": "homogeneous", "sigma_s": [1, 1, 1]},
                                              "fog": {"type": "homogeneous", "sigma_a": [0.1, 0.1, 0.1]}})";

TEST_F(SceneMedia, ObjectsBoundTheirInteriorAndDefaultToTheRendersMediumOutside) {
    write_cubes();
    const Scene s = load(scene(std::string(kTwoMedia) + R"(, "render": {"medium": "fog"})",
                               R"([{"file": "cube.obj", "material": "interface", "interior": "smoke"},
                                   {"file": "cube.obj", "material": "interface", "interior": "fog",
                                    "exterior": "smoke", "transform": [{"translate": [3, 0, 0]}]},
                                   {"file": "tri.obj"}])"));
    ASSERT_EQ(s.objects.size(), 3u);
    const std::uint32_t smoke = s.media[0].name == "smoke" ? 0 : 1, fog = 1 - smoke;
    EXPECT_TRUE(s.objects[0].bounds_medium);
    EXPECT_EQ(s.objects[0].interior, smoke);
    EXPECT_EQ(s.objects[0].exterior, fog);
    EXPECT_EQ(s.objects[1].interior, fog);
    EXPECT_EQ(s.objects[1].exterior, smoke);
    EXPECT_FALSE(s.objects[2].bounds_medium);
    ASSERT_NE(s.interface_material, kNoInterface);
    EXPECT_EQ(s.materials[s.interface_material].type, MaterialType::Interface);
    EXPECT_EQ(s.geometry.material_ids[0], s.interface_material);
    EXPECT_EQ(s.geometry.material_ids[12], s.interface_material);
    EXPECT_EQ(starting_medium(s), fog);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
}

TEST_F(SceneMedia, TheCameraMayStartInsideAnInterior) {
    write_cubes();
    const Scene s = load(std::string("{") + kTwoMedia + R"(, "camera": {"origin": [0.5, 0.5, 0.5], "look_at": [0, 0, 5],
        "medium": "smoke"}, "objects": [{"file": "cube.obj", "material": "interface", "interior": "smoke"}]})");
    EXPECT_EQ(s.media[starting_medium(s)].name, "smoke");
    EXPECT_EQ(s.render_medium, kNoMedium);
}

TEST_F(SceneMedia, AWarningForAnOpaqueBoundaryAndForAnOpenOne) {
    write_cubes();
    load(scene(kTwoMedia, R"([{"file": "cube.obj", "interior": "smoke"}])"));
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("/objects/0/interior"), std::string::npos) << diag.warnings[0];
    EXPECT_NE(diag.warnings[0].find("never entered"), std::string::npos) << diag.warnings[0];
    diag.warnings.clear();
    load(scene(kTwoMedia, R"([{"file": "open_cube.obj", "material": "interface", "interior": "smoke"}])"));
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("not closed (4 edges"), std::string::npos) << diag.warnings[0];
}

TEST_F(SceneMedia, BadObjectMediaNameTheirKey) {
    write_cubes();
    expect_error(scene(kTwoMedia, R"([{"file": "cube.obj", "interior": "milk"}])"), ": /objects/0/interior",
                 "no medium 'milk' in /media");
    expect_error(scene(kTwoMedia, R"([{"file": "cube.obj", "interior": "smoke", "exterior": 3}])"),
                 ": /objects/0/exterior", "expected a string");
    expect_error(scene(kTwoMedia, R"([{"file": "cube.obj", "exterior": "smoke"}])"), ": /objects/0/exterior",
                 "needs 'interior'");
    expect_error(std::string("{") + kTwoMedia + R"(, "camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0],
                     "medium": "milk"}, "objects": [{"file": "cube.obj"}]})",
                 ": /camera/medium", "no medium 'milk' in /media");
}

// The shared cloud (../shared/models/vdb/cloud.vdb) as a medium named "cloud".
std::string cloud_media() {
    return R"("media": {"cloud": {"type": "grid", "file": ")" +
           (std::filesystem::path(SOMBRA_SHARED_DIR) / "models/vdb/cloud.vdb").string() +
           R"(", "sigma_s": [10, 10, 10], "scale": 2}})";
}

TEST_F(SceneMedia, AGridMediumIsPlacedByTheObjectItFills) {
    if (!std::filesystem::exists(std::filesystem::path(SOMBRA_SHARED_DIR) / "models/vdb/cloud.vdb"))
        GTEST_SKIP() << "needs ../shared/models/vdb/cloud.vdb";
    write_cubes();
    const Scene s = load(scene(cloud_media(), R"([{"file": "cube.obj", "material": "interface", "interior": "cloud",
                                                   "transform": [{"translate": [5, 0, 0]}]}])"));
    ASSERT_EQ(s.media.size(), 2u);  // the medium as named, and the object's placement of it
    const std::uint32_t placed = s.objects[0].interior;
    ASSERT_EQ(placed, 1u);
    const Medium& m = s.media[placed];
    ASSERT_TRUE(m.density);
    EXPECT_FLOAT_EQ(m.sigma_s.x, 20.0f);
    // Voxel (1, 4, 1), dense (1, 1, 1), sits at −1 + (i + 0.5)/32, moved by +5 in x.
    const Vec3 q =
        transform_point(m.world_to_grid, {5.0f - 1.0f + 1.5f / 32.0f, -1.0f + 4.5f / 32.0f, -1.0f + 1.5f / 32.0f});
    EXPECT_NEAR(q.x, 1.0f, 1e-4f);
    EXPECT_NEAR(q.y, 1.0f, 1e-4f);
    EXPECT_NEAR(q.z, 1.0f, 1e-4f);

    expect_error(scene(cloud_media() + R"(, "render": {"medium": "cloud"})"), ": /render/medium",
                 "the grid medium 'cloud' cannot fill the scene");
    expect_error(scene(cloud_media(), R"([{"file": "cube.obj", "material": "interface", "interior": "cloud",
                                           "exterior": "cloud"}])"),
                 ": /objects/0/exterior", "a grid medium fills only the interior");
    const std::string missing_grid = R"("media": {"cloud": {"type": "grid", "grid": "smoke", "file": ")" +
                                     (std::filesystem::path(SOMBRA_SHARED_DIR) / "models/vdb/cloud.vdb").string() +
                                     R"("}})";
    expect_error(scene(missing_grid), ": /media/cloud/grid", "no grid 'smoke' (the file has 'density')");
}

// Where the grid placed as `m` puts the shared cloud's voxel (1, 4, 1), whose
// dense coordinates are (1, 1, 1), when the object moves it by `offset`.
void expect_cloud_at(const Medium& m, Vec3 offset) {
    ASSERT_TRUE(m.density);
    const Vec3 q = transform_point(m.world_to_grid,
                                   offset + Vec3{-1.0f + 1.5f / 32.0f, -1.0f + 4.5f / 32.0f, -1.0f + 1.5f / 32.0f});
    EXPECT_NEAR(q.x, 1.0f, 1e-4f);
    EXPECT_NEAR(q.y, 1.0f, 1e-4f);
    EXPECT_NEAR(q.z, 1.0f, 1e-4f);
}

TEST_F(SceneMedia, EachInstanceAndEachMomentPlacesItsOwnGrid) {
    if (!std::filesystem::exists(std::filesystem::path(SOMBRA_SHARED_DIR) / "models/vdb/cloud.vdb"))
        GTEST_SKIP() << "needs ../shared/models/vdb/cloud.vdb";
    write_cubes();
    const Scene drawn = load(scene(cloud_media(), R"([{"file": "cube.obj", "material": "interface",
        "interior": "cloud", "transform": [{"translate": [0, 2, 0]}],
        "instances": [[], [{"translate": [3, 0, 0]}]]}])"));
    ASSERT_EQ(drawn.instances.size(), 2u);
    ASSERT_EQ(drawn.media.size(), 3u);  // the medium as named, and one placement a drawing
    EXPECT_EQ(drawn.instances[0].interior, 1u);
    EXPECT_EQ(drawn.instances[1].interior, 2u);
    expect_cloud_at(drawn.media[1], {0, 2, 0});
    expect_cloud_at(drawn.media[2], {3, 2, 0});

    Scene moving = load(scene(cloud_media() + R"(, "animation": {"fps": 1, "frames": [0, 1]})",
                              R"([{"file": "cube.obj", "material": "interface", "interior": "cloud",
        "transform": {"keys": [{"time": 0, "transform": []}, {"time": 1, "transform": [{"translate": [0, 0, 4]}]}]},
        "instances": [[{"translate": [-2, 0, 0]}]]}])"));
    ASSERT_EQ(moving.instances.size(), 1u);
    const std::uint32_t placed = moving.instances[0].interior;
    ASSERT_EQ(placed, 1u);
    expect_cloud_at(moving.media[placed], {-2, 0, 0});
    set_scene_time(moving, 0.5, "s.json");
    expect_cloud_at(moving.media[placed], {-2, 0, 2});
    set_scene_time(moving, 1.0, "s.json");
    expect_cloud_at(moving.media[placed], {-2, 0, 4});

    expect_error(scene(cloud_media(), R"([{"file": "cube.obj", "material": "interface", "interior": "cloud",
                                           "instances": [[], [{"scale": 2e-15}]]}])"),
                 ": /objects/0/instances/1", "transforms together are not invertible");
}

TEST_F(SceneMedia, ARoughDielectricIsGltfsRoughTransmission) {
    const Scene s =
        load(with_material(R"({"type": "dielectric", "ior": 1.4, "kt": [0.5, 0.6, 0.7], "roughness": 0.3})"));
    const Material& m = s.materials[s.geometry.material_ids[0]];
    EXPECT_EQ(m.type, MaterialType::Pbr);
    EXPECT_FLOAT_EQ(m.roughness, 0.3f);
    EXPECT_FLOAT_EQ(m.ior, 1.4f);
    EXPECT_EQ(m.base_color, (Vec3{0.5f, 0.6f, 0.7f}));
    EXPECT_EQ(m.transmission, 1.0f);
    EXPECT_GT(m.thickness, 0.0f);  // refracts into a volume, not a thin wall
    EXPECT_EQ(m.metallic, 0.0f);
    const Scene smooth = load(with_material(R"({"type": "dielectric", "roughness": 0})"));
    EXPECT_EQ(smooth.materials[smooth.geometry.material_ids[0]].type, MaterialType::Dielectric);
}

}  // namespace
}  // namespace sombra
