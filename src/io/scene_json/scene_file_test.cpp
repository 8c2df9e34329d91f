#include "io/scene_json/scene_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;

// A folder of tiny meshes and a scene file on disk, shared by the tests.
class SceneFile : public testing::SceneFileTest {
protected:
    static void SetUpTestSuite() {
        make_folder("scene_file_test");
        fs::create_directories(dir / "models");
        // The plane x + y = 1 with its normal at every corner.
        write(dir / "tilted.obj", "v 1 0 0\nv 0 1 0\nv 1 0 1\nvn 0.70710678 0.70710678 0\nf 1//1 2//1 3//1\n");
        // Two triangles with two MTL materials.
        write(dir / "two.mtl", "newmtl red\nKd 1 0 0\nnewmtl shiny\nKd 0.2 0.2 0.2\nKs 0.5 0.5 0.5\nNs 20\n");
        write(dir / "two.obj",
              "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nusemtl red\nf 1 2 3\nusemtl shiny\nf 2 4 3\n");
        write(scene_path, "{}");
    }
};

constexpr const char* kCamera = R"("camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]})";
constexpr const char* kObjects = R"("objects": [{"file": "tri.obj"}])";

// A valid scene plus `members`; pass members naming "camera" or "objects" through the other helpers.
std::string scene(const std::string& members) {
    return "{" + members + (members.empty() ? "" : ", ") + kCamera + ", " + kObjects + "}";
}
std::string scene_with_camera(const std::string& camera) { return "{\"camera\": " + camera + ", " + kObjects + "}"; }
std::string scene_with_objects(const std::string& members) { return std::string("{") + kCamera + ", " + members + "}"; }
std::string scene_with_object(const std::string& object, const std::string& materials = "") {
    return scene_with_objects((materials.empty() ? "" : "\"materials\": " + materials + ", ") + "\"objects\": [" +
                              object + "]");
}

struct BadScene {
    const char* label;
    std::string text;
    std::string where;  // after "scene path"; a JSON pointer is preceded by ": "
    std::string message_part;
};

TEST_F(SceneFile, BadScenesNameWhereAndWhat) {
    const std::string kd_ok = R"("kd": [0.5, 0.5, 0.5])";
    const std::vector<BadScene> cases = {
        {"malformed", "{\n  \"render\": {\"width\": 10,}\n}", ":2:26", "unexpected '}'"},
        {"number overflow", "{\n\"render\": {\"seed\": 1e999}}", ":2:20", "number overflow"},
        {"not an object", "[1, 2]", "", "expected an object"},
        {"duplicate key", scene(R"("render": {"width": 10, "width": 20})"), ": /render/width", "duplicate key 'width'"},
        {"unknown top key", scene(R"("rendr": {})"), ": /rendr", "unknown key 'rendr'"},
        {"unknown nested key", scene(R"("render": {"widht": 10})"), ": /render/widht", "unknown key 'widht'"},
        {"width as string", scene(R"("render": {"width": "640"})"), ": /render/width", "expected an integer"},
        {"fractional spp", scene(R"("render": {"spp": 1.5})"), ": /render/spp", "expected an integer"},
        {"short background", scene(R"("background": [1, 2])"), ": /background", "expected an array of 3 numbers"},
        {"background of strings", scene(R"("background": ["a", 0, 0])"), ": /background",
         "expected an array of 3 numbers"},
        {"number beyond float", scene(R"("background": [1e39, 0, 0])"), ": /background/0", "number out of range"},
        {"negative background", scene(R"("background": [-1, 0, 0])"), ": /background", "non-negative"},
        {"spp 0", scene(R"("render": {"spp": 0})"), ": /render/spp", "between 1 and 65536"},
        {"width 0", scene(R"("render": {"width": 0})"), ": /render/width", "between 1 and 32768"},
        {"width 100000", scene(R"("render": {"width": 100000})"), ": /render/width", "between 1 and 32768"},
        {"too many pixels", scene(R"("render": {"width": 32768, "height": 32768})"), ": /render", "exceeds the limit"},
        {"negative seed", scene(R"("render": {"seed": -1})"), ": /render/seed", "non-negative"},
        {"missing objects", std::string("{") + kCamera + "}", ": /objects", "missing required key 'objects'"},
        {"empty objects", scene_with_objects(R"("objects": [])"), ": /objects", "at least one object"},
        {"objects not array", scene_with_objects(R"("objects": {"file": "tri.obj"})"), ": /objects",
         "expected an array"},
        {"missing camera", std::string("{") + kObjects + "}", ": /camera", "missing required key 'camera'"},
        {"both camera forms",
         scene_with_camera(
             R"({"origin": [0,0,0], "look_at": [0,0,-1], "left": [1,0,0], "up": [0,1,0], "forward": [0,0,-1]})"),
         ": /camera", "mixes"},
        {"no camera form", scene_with_camera(R"({"origin": [0,0,0], "up": [0,1,0]})"), ": /camera", "needs"},
        {"basis missing forward", scene_with_camera(R"({"origin": [0,0,0], "left": [1,0,0], "up": [0,1,0]})"),
         ": /camera/forward", "missing required key 'forward'"},
        {"basis not perpendicular",
         scene_with_camera(R"({"origin": [0,0,0], "left": [1,0,0], "up": [0.05,1,0], "forward": [0,0,-1]})"),
         ": /camera", "'left' and 'up' are not perpendicular (angle 87.1°)"},
        {"basis zero vector",
         scene_with_camera(R"({"origin": [0,0,0], "left": [1,0,0], "up": [0,1,0], "forward": [0,0,0]})"),
         ": /camera/forward", "is zero"},
        {"up parallel", scene_with_camera(R"({"origin": [0,0,0], "look_at": [0,5,0]})"), ": /camera/up", "parallel"},
        {"look_at at origin", scene_with_camera(R"({"origin": [1,2,3], "look_at": [1,2,3]})"), ": /camera/look_at",
         "same point"},
        {"fov 0", scene_with_camera(R"({"origin": [0,0,5], "look_at": [0,0,0], "fov": 0})"), ": /camera/fov",
         "strictly between 0 and 180"},
        {"fov 180", scene_with_camera(R"({"origin": [0,0,5], "look_at": [0,0,0], "fov": 180})"), ": /camera/fov",
         "strictly between 0 and 180"},
        {"unknown material", scene_with_object(R"({"file": "tri.obj", "material": "foo"})"), ": /objects/0/material",
         "unknown material 'foo'"},
        {"unknown material type",
         scene_with_object(R"({"file": "tri.obj"})", R"({"m": {"type": "glass", "kd": [0,0,0]}})"),
         ": /materials/m/type", "unknown material type 'glass'"},
        {"material without type", scene_with_object(R"({"file": "tri.obj"})", R"({"m": {"kd": [0,0,0]}})"),
         ": /materials/m/type", "missing required key 'type'"},
        {"kd out of range",
         scene_with_object(R"({"file": "tri.obj"})", R"({"m": {"type": "diffuse", "kd": [0.5, 1.2, 0]}})"),
         ": /materials/m/kd", "kd components must lie in [0, 1]"},
        {"ks below 0",
         scene_with_object(R"({"file": "tri.obj"})",
                           R"({"m": {"type": "phong", )" + kd_ok + R"(, "ks": [-0.1, 0, 0], "shininess": 1}})"),
         ": /materials/m/ks", "ks components must lie in [0, 1]"},
        {"negative shininess",
         scene_with_object(R"({"file": "tri.obj"})",
                           R"({"m": {"type": "phong", )" + kd_ok + R"(, "ks": [0.1, 0.1, 0.1], "shininess": -2}})"),
         ": /materials/m/shininess", "non-negative"},
        {"phong without ks", scene_with_object(R"({"file": "tri.obj"})", R"({"m": {"type": "phong", )" + kd_ok + "}}"),
         ": /materials/m/ks", "missing required key 'ks'"},
        {"diffuse with shininess",
         scene_with_object(R"({"file": "tri.obj"})", R"({"m": {"type": "diffuse", )" + kd_ok + R"(, "shininess": 3}})"),
         ": /materials/m/shininess", "only to phong"},
        {"unknown light type", scene(R"("lights": [{"type": "area", "position": [0,0,0], "intensity": [1,1,1]}])"),
         ": /lights/0/type", "unknown light type 'area'"},
        {"negative intensity", scene(R"("lights": [{"position": [0,0,0], "intensity": [1,-1,1]}])"),
         ": /lights/0/intensity", "non-negative"},
        {"light without position", scene(R"("lights": [{"type": "point", "intensity": [1,1,1]}])"),
         ": /lights/0/position", "missing required key 'position'"},
        {"missing mesh file", scene_with_object(R"({"file": "models/x.obj"})"), ": /objects/0/file",
         "cannot open 'models/x.obj': no such file"},
        {"mesh path a folder", scene_with_object(R"({"file": "models"})"), ": /objects/0/file", "folder"},
        {"mesh path the scene", scene_with_object(R"({"file": "scene.json"})"), ": /objects/0/file",
         "scene file itself"},
        {"object unknown key", scene_with_object(R"({"file": "tri.obj", "transfrom": []})"), ": /objects/0/transfrom",
         "unknown key 'transfrom'"},
        {"matrix last row",
         scene_with_object(R"({"file": "tri.obj", "transform": [{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1]}]})"),
         ": /objects/0/transform/0/matrix", "last row must be [0, 0, 0, 1]"},
        {"matrix of 12",
         scene_with_object(R"({"file": "tri.obj", "transform": [{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0]}]})"),
         ": /objects/0/transform/0/matrix", "16 numbers"},
        {"singular matrix",
         scene_with_object(R"({"file": "tri.obj", "transform": [{"matrix": [1,2,3,0, 4,5,6,0, 5,7,9,0, 0,0,0,1]}]})"),
         ": /objects/0/transform/0/matrix", "not invertible"},
        {"scale 0", scene_with_object(R"({"file": "tri.obj", "transform": [{"translate": [1,2,3]}, {"scale": 0}]})"),
         ": /objects/0/transform/1/scale", "non-zero"},
        {"scale with a zero axis", scene_with_object(R"({"file": "tri.obj", "transform": [{"scale": [1, 0, 1]}]})"),
         ": /objects/0/transform/0/scale", "non-zero"},
        {"two ops in one step",
         scene_with_object(R"({"file": "tri.obj", "transform": [{"scale": 2, "translate": [1,1,1]}]})"),
         ": /objects/0/transform/0", "exactly one key"},
        {"unknown op", scene_with_object(R"({"file": "tri.obj", "transform": [{"shear": 2}]})"),
         ": /objects/0/transform/0/shear", "unknown transform step 'shear'"},
        {"zero rotation axis",
         scene_with_object(R"({"file": "tri.obj", "transform": [{"rotate": {"axis": [0,0,0], "degrees": 5}}]})"),
         ": /objects/0/transform/0/rotate/axis", "axis is zero"},
        {"overflowing transform",
         scene_with_object(R"({"file": "tri.obj", "transform": [{"scale": 1e30}, {"scale": 1e30}]})"),
         ": /objects/0/transform", "overflows"},
    };
    for (const BadScene& c : cases) {
        SCOPED_TRACE(c.label);
        try {
            load(c.text);
            ADD_FAILURE() << "no error for: " << c.text;
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), scene_path.string() + c.where);
            EXPECT_NE(e.message().find(c.message_part), std::string::npos) << e.message();
            EXPECT_EQ(e.message().find('\n'), std::string::npos);
        }
    }
}

TEST_F(SceneFile, MalformedJsonMessageDropsParserPrefix) {
    try {
        load("{\"objects\" 1}");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), scene_path.string() + ":1:12");
        EXPECT_EQ(e.message(), "syntax error while parsing object separator - unexpected number literal; expected ':'");
    }
}

TEST_F(SceneFile, MissingSceneFileIsAnError) {
    EXPECT_THROW(load_scene_file(dir / "nope.json", diag), Error);
    EXPECT_THROW(load_scene_file(dir / "models", diag), Error);
}

TEST_F(SceneFile, DefaultsApply) {
    const LoadedScene loaded = load_scene_text(scene(""), scene_path, diag);
    const RenderSettings& r = loaded.settings;
    EXPECT_EQ(r.width, 640);
    EXPECT_EQ(r.height, 480);
    EXPECT_EQ(r.spp, 1);
    EXPECT_EQ(r.seed, 0u);
    const Scene& s = loaded.scene;
    EXPECT_EQ(s.background, Vec3(0.0f));
    EXPECT_TRUE(s.lights.empty());
    ASSERT_TRUE(s.camera.look_at.has_value());
    EXPECT_FALSE(s.camera.basis.has_value());
    EXPECT_EQ(s.camera.look_at->up, Vec3(0, 1, 0));
    EXPECT_EQ(s.camera.look_at->fov_degrees, 45.0f);
    EXPECT_EQ(s.geometry.triangle_count(), 1u);
    ASSERT_EQ(s.geometry.material_ids.size(), 1u);
    ASSERT_LT(s.geometry.material_ids[0], s.materials.size());
    EXPECT_EQ(s.materials[s.geometry.material_ids[0]].kd, Vec3(0.8f));  // a face without material
    EXPECT_TRUE(diag.warnings.empty());
}

TEST_F(SceneFile, SettingsAndSectionsAreRead) {
    const LoadedScene loaded =
        load_scene_text(scene(
                            R"("render": {"width": 320, "height": 200, "spp": 16, "seed": 18446744073709551615},
           "background": [0.1, 0.2, 0.3],
           "materials": {"gold": {"type": "phong", "kd": [0.4, 0.3, 0.1], "ks": [0.5, 0.4, 0.2], "shininess": 0, "ke": [0, 0, 7]}},
           "lights": [{"type": "point", "position": [1, 2, 3], "intensity": [10, 20, 30]}, {"position": [0, 9, 0], "intensity": [0, 0, 0]}])"),
                        scene_path, diag);
    const RenderSettings& r = loaded.settings;
    EXPECT_EQ(r.width, 320);
    EXPECT_EQ(r.height, 200);
    EXPECT_EQ(r.spp, 16);
    EXPECT_EQ(r.seed, 18446744073709551615ull);
    const Scene& s = loaded.scene;
    EXPECT_EQ(s.background, Vec3(0.1f, 0.2f, 0.3f));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].position, Vec3(1, 2, 3));
    EXPECT_EQ(s.lights[0].intensity, Vec3(10, 20, 30));
    ASSERT_GE(s.materials.size(), 1u);
    const Material& gold = s.materials[0];
    EXPECT_EQ(gold.name, "gold");
    EXPECT_EQ(gold.type, MaterialType::Phong);
    EXPECT_EQ(gold.ks, Vec3(0.5f, 0.4f, 0.2f));
    EXPECT_EQ(gold.shininess, 0.0f);
    EXPECT_EQ(gold.ke, Vec3(0, 0, 7));
}

TEST_F(SceneFile, BasisCameraIsKeptAsWritten) {
    const Scene s =
        load(scene_with_camera(R"({"origin": [1,2,3], "left": [-2,0,0], "up": [0,1.5,0], "forward": [0,0,-1]})"));
    ASSERT_TRUE(s.camera.basis.has_value());
    EXPECT_FALSE(s.camera.look_at.has_value());
    EXPECT_EQ(s.camera.basis->origin, Vec3(1, 2, 3));
    EXPECT_EQ(s.camera.basis->left, Vec3(-2, 0, 0));
    EXPECT_EQ(s.camera.basis->up, Vec3(0, 1.5f, 0));
    EXPECT_EQ(s.camera.basis->forward, Vec3(0, 0, -1));
}

TEST_F(SceneFile, EnergyGainWarns) {
    load(scene(
        R"("materials": {"hot": {"type": "phong", "kd": [0.7, 0.5, 0.5], "ks": [0.4, 0.5, 0.5], "shininess": 10}})"));
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("/materials/hot"), std::string::npos) << diag.warnings[0];
}

TEST_F(SceneFile, TransformsApplyInListedOrder) {
    const auto vertex = [&](const std::string& transform) {
        const Scene s = load(scene_with_object(R"({"file": "tri.obj", "transform": )" + transform + "}"));
        return s.geometry.positions.at(s.geometry.triangles.at(0)[0]);  // file vertex (1, 0, 0)
    };
    EXPECT_EQ(vertex(R"([{"scale": 2}, {"translate": [1, 0, 0]}])"), Vec3(3, 0, 0));
    EXPECT_EQ(vertex(R"([{"translate": [1, 0, 0]}, {"scale": 2}])"), Vec3(4, 0, 0));
    EXPECT_EQ(vertex(R"([{"scale": [3, 1, 1]}])"), Vec3(3, 0, 0));
    EXPECT_EQ(vertex(R"([{"rotate": {"axis": [0, 1, 0], "degrees": 90}}])"), Vec3(0, 0, -1));
    EXPECT_EQ(vertex(R"([{"matrix": [1,0,0,5, 0,1,0,6, 0,0,1,7, 0,0,0,1]}])"), Vec3(6, 6, 7));
    EXPECT_EQ(vertex(R"([{"matrix": [0,-1,0,0, 1,0,0,0, 0,0,1,0, 0,0,0,1]}])"), Vec3(0, 1, 0));
    EXPECT_EQ(vertex("[]"), Vec3(1, 0, 0));
}

TEST_F(SceneFile, NormalsFollowTheInverseTranspose) {
    const Scene s = load(scene_with_object(R"({"file": "tilted.obj", "transform": [{"scale": [1, 4, 1]}]})"));
    const TriangleMesh& g = s.geometry;
    ASSERT_TRUE(g.has_normals());
    ASSERT_EQ(g.normal_indices.size(), 1u);
    const Index3 t = g.triangles[0];
    const Vec3 e1 = g.positions[t[1]] - g.positions[t[0]], e2 = g.positions[t[2]] - g.positions[t[0]];
    for (int c = 0; c < 3; ++c) {
        ASSERT_NE(g.normal_indices[0][c], kNoNormal);
        const Vec3 n = g.normals.at(g.normal_indices[0][c]);
        EXPECT_NEAR(length(n), 1.0f, 1e-6f);
        EXPECT_NEAR(dot(n, normalize(e1)), 0.0f, 1e-6f);
        EXPECT_NEAR(dot(n, normalize(e2)), 0.0f, 1e-6f);
        EXPECT_GT(n.x, 0.0f);  // still on the side the file's normal was
    }
}

TEST_F(SceneFile, ObjectsConcatenateWithOffsetsAndMaterials) {
    const std::string materials = R"({"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}})";
    const Scene s = load(scene_with_object(
        R"({"file": "two.obj", "material": "grey"}, {"file": "tilted.obj", "transform": [{"translate": [0, 0, 10]}]}, {"file": "two.obj"})",
        materials));
    const TriangleMesh& g = s.geometry;
    ASSERT_EQ(g.triangle_count(), 5u);
    ASSERT_EQ(g.positions.size(), 4u + 3u + 4u);
    // Indices point at the right object's vertices.
    EXPECT_EQ(g.positions[g.triangles[2][0]], Vec3(1, 0, 10));
    EXPECT_EQ(g.triangles[3], (Index3{7, 8, 9}));
    EXPECT_EQ(g.triangles[4], (Index3{8, 10, 9}));
    // Only the middle object has normals; the others are marked as having none.
    ASSERT_EQ(g.normal_indices.size(), 5u);
    EXPECT_EQ(g.normal_indices[0], (Index3{kNoNormal, kNoNormal, kNoNormal}));
    EXPECT_NE(g.normal_indices[2][0], kNoNormal);
    EXPECT_EQ(g.normal_indices[4], (Index3{kNoNormal, kNoNormal, kNoNormal}));
    // Loading derives which triangles have all three (TriangleMesh::complete_normals).
    EXPECT_EQ(g.complete_normals, std::vector<std::uint64_t>{0b00100u});
    EXPECT_TRUE(g.complete_uvs.empty());
    // The override gives both triangles "grey"; without it, the file's own materials.
    ASSERT_EQ(g.material_ids.size(), 5u);
    EXPECT_EQ(s.materials.at(g.material_ids[0]).name, "grey");
    EXPECT_EQ(s.materials.at(g.material_ids[1]).name, "grey");
    const Material& red = s.materials.at(g.material_ids[3]);
    const Material& shiny = s.materials.at(g.material_ids[4]);
    EXPECT_EQ(red.name, "red");
    EXPECT_EQ(red.kd, Vec3(1, 0, 0));
    EXPECT_EQ(shiny.type, MaterialType::Phong);
    EXPECT_EQ(shiny.ks, Vec3(0.5f));
}

TEST_F(SceneFile, RelativeMeshPathsFollowTheSceneFolder) {
    const fs::path sub = dir / "models" / "nested.json";
    std::ofstream(sub) << scene_with_object(R"({"file": "../tri.obj"})");
    const Scene s = load_scene_file(sub, diag).scene;
    EXPECT_EQ(s.geometry.triangle_count(), 1u);
}

// The benchmark scenes of shared/scenes, with the triangle counts of their README.
TEST(SharedScenes, LoadWithTheirTriangleCounts) {
    const fs::path scenes = fs::path(SOMBRA_SHARED_DIR) / "scenes";
    if (!fs::exists(scenes / "bunny.json")) GTEST_SKIP() << "shared/ not found at " << SOMBRA_SHARED_DIR;
    const std::pair<const char*, std::size_t> expected[] = {{"bunny.json", 69453},
                                                            {"dragon.json", 871416},
                                                            {"cornell.json", 36},
                                                            {"phong.json", 6826},
                                                            {"manylights.json", 6322}};
    for (const auto& [name, triangles] : expected) {
        SCOPED_TRACE(name);
        Diagnostics diag;
        const Scene s = load_scene_file(scenes / name, diag).scene;
        EXPECT_EQ(s.geometry.triangle_count(), triangles);
        EXPECT_EQ(s.geometry.material_ids.size(), triangles);
        for (const Index3& t : s.geometry.triangles)
            for (std::uint32_t v : t) ASSERT_LT(v, s.geometry.positions.size());
        for (const Vec3& p : s.geometry.positions) ASSERT_TRUE(is_finite(p));
    }
}

// Every scene the repository ships must load, warning-free, except for the
// one warning a scene asks for by reading a shared environment map with
// "clamp_negative" (the shared maps hold a few negative values). Scenes that
// use ../shared are skipped, with a note, where it is absent.
TEST(RepositoryScenes, AllLoad) {
    const fs::path scenes = fs::path(SOMBRA_SOURCE_DIR) / "scenes";
    if (!fs::is_directory(scenes)) GTEST_SKIP() << "no scenes/ at " << SOMBRA_SOURCE_DIR;
    const bool have_shared = fs::is_directory(fs::path(SOMBRA_SHARED_DIR) / "models");
    int loaded = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(scenes)) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().string());
        std::ifstream in(entry.path());
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (!have_shared && text.find("../../shared/") != std::string::npos) {
            std::cout << "note: " << entry.path().filename() << " needs shared/, skipped\n";
            continue;
        }
        Diagnostics diag;
        const Scene s = load_scene_file(entry.path(), diag).scene;
        EXPECT_GT(s.geometry.triangle_count(), 0u);
        for (const std::string& w : diag.warnings) {
            const bool asked_for = text.find("\"clamp_negative\": true") != std::string::npos &&
                                   w.find("negative values read as 0") != std::string::npos;
            EXPECT_TRUE(asked_for) << w;
        }
        ++loaded;
    }
    EXPECT_GT(loaded, 0);
}

TEST(SharedScenes, CornellKeepsItsMtlMaterials) {
    const fs::path path = fs::path(SOMBRA_SHARED_DIR) / "scenes" / "cornell.json";
    if (!fs::exists(path)) GTEST_SKIP() << "shared/ not found at " << SOMBRA_SHARED_DIR;
    Diagnostics diag;
    const Scene s = load_scene_file(path, diag).scene;
    // The light quad (2 triangles) emits Ke 17 12 4; nothing else does.
    int emitting = 0;
    for (std::uint32_t id : s.geometry.material_ids) emitting += s.materials.at(id).ke == Vec3(17, 12, 4) ? 1 : 0;
    EXPECT_EQ(emitting, 2);
}

TEST(SharedScenes, BunnyPlacementMatchesItsReadme) {
    const fs::path path = fs::path(SOMBRA_SHARED_DIR) / "scenes" / "bunny.json";
    if (!fs::exists(path)) GTEST_SKIP() << "shared/ not found at " << SOMBRA_SHARED_DIR;
    Diagnostics diag;
    const Scene s = load_scene_file(path, diag).scene;
    // Scaled by 10 and moved to stand on y = 0 (bunny's base at y = 0.03299 in the file).
    float min_y = INFINITY;
    for (std::size_t i = 0; i + 2 < s.geometry.triangle_count(); ++i)
        for (std::uint32_t v : s.geometry.triangles[i]) min_y = std::fmin(min_y, s.geometry.positions[v].y);
    EXPECT_NEAR(min_y, 0.0f, 1e-3f);
}

}  // namespace
}  // namespace sombra
