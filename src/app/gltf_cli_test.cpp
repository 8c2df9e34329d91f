// glTF through the command line (spec §13): a node tree renders as the same
// mesh placed by a scene file's transform; the Draco bunny renders as its
// uncompressed twin; the quick look takes the file's camera; broken files,
// and every assimp glTF2 test model, end in an image or one error line.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_test_fixture.h"
#include "io/gltf/gltf_test_files.h"
#include "io/mesh_file.h"

namespace sombra {
namespace {

using namespace sombra::cli_test;
using gltf_test::GltfFile;

// A pyramid (four slanted faces on a square base): shading varies with the
// orientation, so a wrong transform shows.
GltfFile pyramid() {
    GltfFile f;
    const std::vector<Vec3> p{{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {0, 1.5f, 0}};
    const std::vector<std::uint32_t> i{0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 0, 2, 1, 0, 3, 2};
    f.add_mesh({{"POSITION", f.add_positions(p)}}, f.add_indices(i));
    return f;
}

// Largest difference between two images of the same size (infinity if not).
float max_difference(const Pfm& a, const Pfm& b) {
    if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size() || a.rgb.empty()) return INFINITY;
    float worst = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) worst = std::max(worst, std::fabs(a.rgb[i] - b.rgb[i]));
    return worst;
}

float sum(const Pfm& image) {
    float total = 0;
    for (const float v : image.rgb) total += v;
    return total;
}

class GltfCli : public CliFixture {
protected:
    // Renders a scene with one object (file, plus JSON for "transform") to NAME.pfm.
    Pfm render_object(const std::string& file, const std::string& transform, const std::string& name) {
        write_text(
            dir_ / (name + ".json"),
            R"({"render": {"width": 48, "height": 36}, "camera": {"origin": [3, 4, 9], "look_at": [0, 0.5, 0], "fov": 40},
                       "materials": {"grey": {"type": "diffuse", "kd": [0.6, 0.6, 0.6]}},
                       "lights": [{"type": "point", "position": [-4, 6, 5], "intensity": [60, 60, 60]}],
                       "objects": [{"file": ")" +
                file + R"(", "material": "grey")" + (transform.empty() ? "" : ", \"transform\": " + transform) + "}]}");
        const RunResult r = run("render " + name + ".json -o " + name + ".pfm --quiet");
        EXPECT_EQ(r.status, 0) << r.err;
        return read_pfm(dir_ / (name + ".pfm"));
    }
};

TEST_F(GltfCli, NodeTreeRendersLikeTheSceneFilesTransform) {
    GltfFile tree = pyramid();
    // Parent: translate (0.5, -0.5, 0) · rotate 30° about +y · scale 1.2; child: a matrix translating x by 0.3.
    const double angle = 30 * 3.14159265358979 / 180;
    tree.add_node({{"translation", {0.5, -0.5, 0}},
                   {"rotation", {0, std::sin(angle / 2), 0, std::cos(angle / 2)}},
                   {"scale", {1.2, 1.2, 1.2}},
                   {"children", {1}}});
    tree.add_node({{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.3, 0, 0, 1}}});
    tree.set_scene({0});
    tree.save(dir_ / "tree.gltf");
    GltfFile flat = pyramid();
    flat.add_node({{"mesh", 0}});
    flat.set_scene({0});
    flat.save(dir_ / "flat.glb");

    const Pfm by_nodes = render_object("tree.gltf", "", "nodes");
    const Pfm by_scene =
        render_object("flat.glb",
                      R"([{"translate": [0.3, 0, 0]}, {"scale": 1.2}, {"rotate": {"axis": [0, 1, 0], "degrees": 30}},
            {"translate": [0.5, -0.5, 0]}])",
                      "scene");
    const Pfm untransformed = render_object("flat.glb", "", "plain");
    EXPECT_GT(sum(by_nodes), 1.0f);
    // The same matrix up to the rounding of composing it in another order.
    EXPECT_LT(max_difference(by_nodes, by_scene), 1e-3f);
    EXPECT_GT(max_difference(by_nodes, untransformed), 0.05f);  // the check can fail
}

TEST_F(GltfCli, DracoBunnyRendersLikeItsUncompressedTwin) {
    const fs::path bunny = fs::path(SOMBRA_SHARED_DIR) / "models" / "gltf" / "bunny.glb";
    if (!fs::exists(bunny)) GTEST_SKIP() << "shared/ not found at " << SOMBRA_SHARED_DIR;
    // The decoded mesh, written back uncompressed.
    Diagnostics diag;
    const LoadedMesh decoded = load_gltf(bunny, diag);
    ASSERT_EQ(decoded.mesh.triangle_count(), 5648u);
    GltfFile twin;
    std::vector<std::uint32_t> indices;
    std::vector<Vec3> normals(decoded.mesh.positions.size());
    for (std::size_t t = 0; t < decoded.mesh.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) {
            indices.push_back(decoded.mesh.triangles[t][std::size_t(c)]);
            normals[decoded.mesh.triangles[t][std::size_t(c)]] =
                decoded.mesh.normals[decoded.mesh.normal_indices[t][std::size_t(c)]];
        }
    twin.add_mesh({{"POSITION", twin.add_positions(decoded.mesh.positions)}, {"NORMAL", twin.add_normals(normals)}},
                  twin.add_indices(indices));
    twin.add_node({{"mesh", 0}});
    twin.set_scene({0});
    twin.save(dir_ / "twin.glb");
    fs::copy_file(bunny, dir_ / "bunny.glb");

    // Through a scene file with a diffuse material: the geometry is compared, not the pbr BSDF.
    const Pfm compressed = render_object("bunny.glb", "", "bunny"), twin_image = render_object("twin.glb", "", "twin");
    EXPECT_GT(sum(compressed), 1.0f);
    EXPECT_LT(max_difference(compressed, twin_image), 1e-4f);  // normals renormalised once more: float rounding
}

TEST_F(GltfCli, QuickLookUsesTheFilesCamera) {
    GltfFile f = pyramid();
    f.add_node({{"mesh", 0}});
    f.add_node({{"camera", 0}, {"translation", {0, 0.5, 6}}});
    f.set_scene({0, 1});
    f.doc["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"aspectRatio", 2.0}, {"znear", 0.1}}}}};
    f.save(dir_ / "cam.gltf");
    RunResult r = run("render cam.gltf -o cam.pfm --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    const Pfm with_camera = read_pfm(dir_ / "cam.pfm");
    EXPECT_EQ(with_camera.width, 640);
    EXPECT_EQ(with_camera.height, 320);  // the file's aspect ratio

    // Without the camera node the automatic framing gives another picture.
    f.set_scene({0});
    f.save(dir_ / "cam.gltf");
    r = run("render cam.gltf -o auto.pfm --width 640 --height 320 --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(max_difference(with_camera, read_pfm(dir_ / "auto.pfm")), 0.05f);
}

TEST_F(GltfCli, BrokenFileIsOneErrorLine) {
    GltfFile f = pyramid();
    f.doc["nodes"] = {{{"children", {1}}}, {{"children", {0}}, {"mesh", 0}}};
    f.doc["scenes"] = {{{"nodes", nlohmann::json::array()}}};
    f.save(dir_ / "cycle.glb");
    expect_input_error(run("render cycle.glb -o out.png"), "cycle.glb: node 0 is its own ancestor");
    write_text(dir_ / "s.json", scene(R"({"width": 32, "height": 24})",
                                      R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})", "", "cycle.glb"));
    expect_input_error(run("render s.json -o out.png"), "node cycle");
    const char junk[] = "glTF\x02\0\0\0 this is not a GLB file at all";
    write_text(dir_ / "junk.glb", std::string(junk, sizeof junk - 1));
    expect_input_error(run("render junk.glb -o out.png"), "junk.glb: the GLB header gives a length");
}

// A member of the wrong JSON type (spec §24) ends the command with one error
// line naming the member's JSON pointer, and no image; so does each of
// assimp's wrongTypes models, which rendered without the member before.
TEST_F(GltfCli, WrongTypeIsOneErrorLineNamingTheMember) {
    GltfFile f = pyramid();
    f.add_node({{"mesh", 0}, {"scale", "big"}});
    f.set_scene({0});
    f.save(dir_ / "model.gltf");
    expect_input_error(run("render model.gltf -o out.png"),
                       "sombra: error: model.gltf: /nodes/0/scale: expected an array of 3 numbers, got a string\n");

    const fs::path root = "/usr/share/assimp/models/glTF2/wrongTypes";
    if (!fs::is_directory(root)) GTEST_SKIP() << root << " not found (Debian package assimp-testmodels)";
    const std::pair<const char*, const char*> cases[] = {
        {"badArray.gltf", "/meshes/0/primitives: expected an array of objects, got an object"},
        {"badNumber.gltf", "/materials/0/normalTexture/scale: expected a number, got a string"},
        {"badObject.gltf", "/materials/0/pbrMetallicRoughness: expected an object, got an array"},
        {"badString.gltf", "/scenes/0/name: expected a string, got 42"},
        {"badUint.gltf",
         "/materials/0/pbrMetallicRoughness/baseColorTexture/index: expected a non-negative integer, got -1"},
        {"badExtension.gltf",
         "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform: "
         "expected an object, got a string"},
    };
    for (const auto& [name, what] : cases) {
        SCOPED_TRACE(name);
        const std::string path = (root / name).string();
        expect_input_error(run("render " + shell_quote(path) + " -o out.png --width 64 --height 48 --quiet"),
                           "sombra: error: " + path + ": " + what + "\n");
    }
}

// Every assimp glTF2 test model through `sombra render` at 64×48: an image
// and exit 0, or one error line and exit 1.
TEST_F(GltfCli, AssimpTestModelsRenderOrFailWithOneLine) {
    const fs::path root = "/usr/share/assimp/models/glTF2";
    if (!fs::is_directory(root)) GTEST_SKIP() << root << " not found (Debian package assimp-testmodels)";
    int rendered = 0, failed = 0;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const std::string ext = entry.path().extension().string();
        if (ext != ".gltf" && ext != ".glb") continue;
        SCOPED_TRACE(entry.path().string());
        fs::remove(dir_ / "out.png");
        const RunResult r = run("render " + shell_quote(entry.path().string()) +
                                " -o out.png --width 64 --height 48 --quiet --threads 2");
        if (r.status == 0) {
            EXPECT_TRUE(fs::exists(dir_ / "out.png"));
            ++rendered;
        } else {
            expect_input_error(r, entry.path().string() + ": ");
            ++failed;
        }
    }
    EXPECT_GE(rendered, 19);
    EXPECT_GE(failed, 5);
}

}  // namespace
}  // namespace sombra
