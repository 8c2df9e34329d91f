// The glTF loader (spec §13) on tiny files written here: the node tree,
// primitives with and without indices, quantized accessors, the uv flip,
// mirroring nodes, materials, lights and cameras; the Draco bunny of
// shared/; and the contract for broken files.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "io/gltf/gltf.h"
#include "io/gltf/gltf_test_files.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"
#include "io/quicklook.h"
#include "io/scene_json/scene_file.h"
#include "scene/transform.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using gltf_test::quad_file;
using testing::TempFolder;

static_assert(sizeof(Vec3) == 12 && sizeof(Vec2) == 8, "the test files write Vec3 and Vec2 arrays as they lie");

LoadedMesh load(const GltfFile& f, const char* name = "m.gltf") {
    TempFolder dir;
    const std::filesystem::path path = dir.path / name;
    f.save(path);
    Diagnostics diag;
    return load_gltf(path, diag);
}

// The world positions of every triangle's corners, in order.
std::vector<Vec3> corners(const TriangleMesh& m) {
    std::vector<Vec3> out;
    for (const Index3& t : m.triangles)
        for (std::uint32_t i : t) out.push_back(m.positions[i]);
    return out;
}

void expect_near(Vec3 a, Vec3 b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(GltfLoader, IndexedAndUnindexedPrimitivesGiveTheSameTriangles) {
    for (const char* name : {"m.gltf", "m.glb"}) {
        SCOPED_TRACE(name);
        GltfFile indexed = quad_file(true), flat = quad_file(false);
        indexed.add_node({{"mesh", 0}});
        indexed.set_scene({0});
        flat.add_node({{"mesh", 0}});
        flat.set_scene({0});
        const LoadedMesh a = load(indexed, name), b = load(flat, name);
        ASSERT_EQ(a.mesh.triangle_count(), 2u);
        EXPECT_EQ(corners(a.mesh), corners(b.mesh));
        EXPECT_TRUE(a.mesh.has_normals());
        EXPECT_FALSE(b.mesh.has_normals());
    }
}

TEST(GltfLoader, TexcoordVIsFlippedToSombrasConvention) {
    GltfFile f = quad_file();
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    const LoadedMesh m = load(f);
    ASSERT_TRUE(m.mesh.has_uvs());
    // glTF (0, 1) at corner (0, 0, 0): the image's bottom-left, sombra's v = 0.
    const Index3 first = m.mesh.uv_indices[0];
    EXPECT_EQ(m.mesh.uvs[first[0]], (Vec2{0, 0}));
    EXPECT_EQ(m.mesh.uvs[first[2]], (Vec2{1, 1}));
}

TEST(GltfLoader, NodeTransformsComposeParentTimesChild) {
    GltfFile f = quad_file();
    // Parent: translate (1, 2, 3) · rotate 90° about +y · scale 2; child: matrix translating x by 0.5.
    const float h = std::sqrt(0.5f);
    f.add_node({{"translation", {1, 2, 3}}, {"rotation", {0, h, 0, h}}, {"scale", {2, 2, 2}}, {"children", {1}}});
    f.add_node({{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 1}}});
    f.set_scene({0});
    const LoadedMesh m = load(f);
    const Transform expected =
        compose(compose(compose(make_translate({0.5f, 0, 0}), make_scale(Vec3{2})), make_rotate({0, 1, 0}, 90)),
                make_translate({1, 2, 3}));
    ASSERT_EQ(m.mesh.positions.size(), 4u);
    const Vec3 file_corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int i = 0; i < 4; ++i)
        expect_near(m.mesh.positions[std::size_t(i)], transform_point(expected, file_corners[i]));
    // Normals follow: +z turned 90° about +y is +x.
    expect_near(m.mesh.normals[0], {1, 0, 0});
}

TEST(GltfLoader, MirroringNodeKeepsTheWindingNormalsSide) {
    GltfFile f = quad_file();
    f.add_node({{"mesh", 0}, {"scale", {-1, 1, 1}}});  // mirror in x: the quad still faces +z
    f.set_scene({0});
    const TriangleMesh m = load(f).mesh;
    for (const Index3& t : m.triangles)
        EXPECT_GT(testing::twice_area_along(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], {0, 0, 1}), 0);
}

TEST(GltfLoader, QuantizedAccessorsAreNormalised) {
    GltfFile f;
    const std::vector<std::int16_t> pos{0, 0, 0, 0, 32767, 0, 0, 0, 32767, 32767, 0, 0};  // VEC3 padded to 8 bytes
    const int pv = f.add_view(pos.data(), pos.size() * 2, 8);
    const int p = f.add_accessor(pv, gltf_test::kShort, 3, "VEC3", true);
    const std::vector<std::uint8_t> uv{0, 255, 255, 0, 128, 0, 0, 0};  // VEC2 padded to 4 bytes... 3 used
    const int uvv = f.add_view(uv.data(), 6);
    const int t = f.add_accessor(uvv, gltf_test::kUnsignedByte, 3, "VEC2", true);
    // TEXCOORD_1 (spec §24) reads the same quantized data.
    f.add_mesh({{"POSITION", p}, {"TEXCOORD_0", t}, {"TEXCOORD_1", t}});
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    f.use_extension("KHR_mesh_quantization", true);
    const LoadedMesh m = load(f, "q.glb");
    ASSERT_EQ(m.mesh.positions.size(), 3u);
    expect_near(m.mesh.positions[1], {1, 0, 0});
    expect_near(m.mesh.positions[2], {1, 1, 0});
    expect_near(Vec3{m.mesh.uvs[0].x, m.mesh.uvs[0].y, 0}, {0, 0, 0});             // (0, 1) flipped
    expect_near(Vec3{m.mesh.uvs[2].x, m.mesh.uvs[2].y, 0}, {128 / 255.0f, 1, 0});  // (128/255, 0) flipped
    EXPECT_EQ(m.mesh.extra_uvs[0].uvs, m.mesh.uvs);
    EXPECT_EQ(m.mesh.extra_uvs[0].indices, m.mesh.uv_indices);

    // Without the extension, integer positions are a wrong component type.
    f.doc.erase("extensionsUsed");
    f.doc.erase("extensionsRequired");
    EXPECT_THROW(load(f, "q.glb"), Error);
}

TEST(GltfLoader, MaterialsBecomePbrWithTheirTextureReferencesKept) {
    GltfFile f = quad_file();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    f.doc["materials"] = {
        {{"name", "red"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.9, 0.2, 0.1, 0.5}},
           {"metallicFactor", 0.25},
           {"roughnessFactor", 0.75},
           {"baseColorTexture",
            {{"index", 0},
             {"texCoord", 0},
             {"extensions",
              {{"KHR_texture_transform", {{"offset", {0.5, 0}}, {"scale", {2, 2}}, {"rotation", 0.1}}}}}}}}},
         {"emissiveFactor", {0.5, 0.25, 0}},
         {"alphaMode", "MASK"},
         {"extensions",
          {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}, {"KHR_materials_ior", {{"ior", 1.33}}}}}}};
    f.doc["textures"] = {{{"source", 0}, {"sampler", 0}}};
    f.doc["images"] = {{{"uri", "red.png"}}};
    f.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}}};
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    f.use_extension("KHR_texture_transform");
    TempFolder dir;
    f.save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedMesh m = load_gltf(dir.path / "m.gltf", diag);
    ASSERT_EQ(m.materials.size(), 1u);
    const Material& red = m.materials[0];
    EXPECT_EQ(red.type, MaterialType::Pbr);
    EXPECT_EQ(red.name, "red");
    EXPECT_EQ(red.base_color, (Vec3{0.9f, 0.2f, 0.1f}));
    EXPECT_FLOAT_EQ(red.metallic, 0.25f);
    EXPECT_FLOAT_EQ(red.roughness, 0.75f);
    EXPECT_FLOAT_EQ(red.ior, 1.33f);
    EXPECT_EQ(red.ke, (Vec3{2.0f, 1.0f, 0.0f}));
    // The texture references as the file gives them, which the material's
    // slots were made from (glTF's own data: the loader's parts keep it, not LoadedMesh).
    Diagnostics parse_diag;
    const gltf::Materials converted =
        gltf::convert_materials(gltf::parse_file(dir.path / "m.gltf", parse_diag), "m.gltf", parse_diag);
    ASSERT_EQ(converted.texture_refs.size(), 1u);
    const GltfMaterialTextures& refs = converted.texture_refs[0];
    EXPECT_EQ(refs.base_color.texture, 0);
    EXPECT_EQ(refs.base_color.uri, "red.png");
    EXPECT_EQ(refs.base_color.wrap_s, GltfWrap::ClampToEdge);
    EXPECT_EQ(refs.base_color.wrap_t, GltfWrap::MirroredRepeat);
    EXPECT_EQ(refs.base_color.offset, (Vec2{0.5f, 0}));
    EXPECT_EQ(refs.base_color.scale, (Vec2{2, 2}));
    EXPECT_FLOAT_EQ(refs.base_color.rotation, 0.1f);
    EXPECT_FALSE(refs.normal.present());
    EXPECT_EQ(refs.alpha_mode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(refs.base_alpha, 0.5f);
    // The transform is applied now: the only complaint is the missing image.
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("'red.png' not found"), std::string::npos) << diag.warnings[0];
}

// A quad and three lights under a translated parent (spec §13, §16): a
// point light 683 cd bright (1 W/sr per unit of colour) moved by its node, a
// spot turned by its node's rotation (its −z axis, turned 90° about +x,
// points along +y), and a sun of 3 × 683 lux.
GltfFile lit_quad() {
    GltfFile f = quad_file();
    const double h = std::sqrt(0.5);
    f.add_node({{"mesh", 0}});
    f.add_node({{"translation", {0, 2, 0}}, {"children", {2, 3, 4}}});
    f.add_node({{"translation", {1, 0, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    f.add_node({{"rotation", {h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    f.add_node({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    f.set_scene({0, 1});
    f.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 2 * 683}},
        {{"type", "spot"}, {"intensity", 683}, {"spot", {{"outerConeAngle", 0.5}, {"innerConeAngle", 0.25}}}},
        {{"type", "directional"}, {"intensity", 3 * 683}}};
    f.use_extension("KHR_lights_punctual");
    return f;
}

TEST(GltfLoader, LightsAreConvertedFromCandelaAndLuxAndPlacedByTheirNode) {
    TempFolder dir;
    lit_quad().save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedMesh m = load_gltf(dir.path / "m.gltf", diag);
    ASSERT_EQ(m.lights.size(), 3u);
    EXPECT_EQ(m.lights[0].type, LightType::Point);
    expect_near(m.lights[0].position, {1, 2, 0});
    expect_near(m.lights[0].intensity, {2, 1, 0.5f}, 1e-6f);
    EXPECT_EQ(m.lights[1].type, LightType::Spot);
    expect_near(m.lights[1].position, {0, 2, 0});
    expect_near(m.lights[1].direction, {0, 1, 0}, 1e-6f);
    expect_near(m.lights[1].intensity, {1, 1, 1}, 1e-6f);
    EXPECT_NEAR(m.lights[1].cos_outer, std::cos(0.5), 1e-6);
    EXPECT_NEAR(m.lights[1].cos_inner, std::cos(0.25), 1e-6);
    EXPECT_EQ(m.lights[2].type, LightType::Directional);
    expect_near(m.lights[2].direction, {0, 0, -1}, 1e-6f);
    expect_near(m.lights[2].intensity, {3, 3, 3}, 1e-6f);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];

    // In a scene file the object's transform moves the lights with the mesh
    // and turns the spot's and the sun's directions.
    dir.write("s.json", R"({"camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]},
        "objects": [{"file": "m.gltf", "transform": [{"rotate": {"axis": [0, 1, 0], "degrees": 90}},
                                                    {"translate": [0, 0, -1]}]}]})");
    const Scene scene = load_scene_file(dir.path / "s.json", diag).scene;
    ASSERT_EQ(scene.lights.size(), 3u);
    expect_near(scene.lights[0].position, {0, 2, -2}, 1e-6f);
    expect_near(scene.lights[1].position, {0, 2, -1}, 1e-6f);
    expect_near(scene.lights[1].direction, {0, 1, 0}, 1e-6f);
    expect_near(scene.lights[2].direction, {-1, 0, 0}, 1e-6f);
}

TEST(GltfLoader, SpotConeAnglesAreCheckedAndEqualAnglesAccepted) {
    for (const auto& [inner, outer, error, warnings] :
         std::vector<std::tuple<double, double, const char*, std::size_t>>{
             {0.5, 0.5, "", 0},  // Blender's spot without blend: inner = outer
             {0.7, 0.5, "", 1},  // inner > outer: read as equal, with a warning
             {0.0, 0.0, "outerConeAngle", 0},
             {0.0, 1.6, "outerConeAngle", 0},  // beyond π/2
             {-0.1, 0.5, "innerConeAngle", 0}}) {
        GltfFile f = lit_quad();
        f.doc["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"] = {{"innerConeAngle", inner},
                                                                           {"outerConeAngle", outer}};
        TempFolder dir;
        f.save(dir.path / "m.gltf");
        Diagnostics diag;
        SCOPED_TRACE(std::to_string(inner) + " " + std::to_string(outer));
        if (*error) {
            try {
                load_gltf(dir.path / "m.gltf", diag);
                ADD_FAILURE() << "expected an error";
            } catch (const Error& e) {
                EXPECT_NE(e.message().find(error), std::string::npos) << e.message();
                EXPECT_NE(e.message().find("KHR_lights_punctual light 1"), std::string::npos) << e.message();
            }
            continue;
        }
        const LoadedMesh m = load_gltf(dir.path / "m.gltf", diag);
        ASSERT_EQ(m.lights.size(), 3u);
        EXPECT_EQ(m.lights[1].cos_inner, m.lights[1].cos_outer);
        EXPECT_NEAR(m.lights[1].cos_outer, std::cos(0.5), 1e-6);
        EXPECT_EQ(diag.warnings.size(), warnings);
    }
}

TEST(GltfLoader, QuickLookUsesTheFilesFirstCamera) {
    GltfFile f = lit_quad();
    const float h = std::sqrt(0.5f);
    // Camera 1 is placed first in the tree, camera 0 (the first) later: 0 wins.
    f.add_node({{"camera", 1}});
    f.add_node({{"camera", 0}, {"translation", {0, 0, 4}}, {"rotation", {0, h, 0, h}}});  // looks along −x
    f.doc["scenes"][0]["nodes"] = {0, 1, 5, 6};
    f.doc["cameras"] = {{{"type", "perspective"},
                         {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}}}},
                        {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
    TempFolder dir;
    f.save(dir.path / "m.gltf");
    Diagnostics diag;
    const LoadedScene loaded = make_quicklook_scene(dir.path / "m.gltf", diag);
    const Scene& scene = loaded.scene;
    ASSERT_TRUE(scene.camera.look_at);
    expect_near(scene.camera.look_at->origin, {0, 0, 4});
    expect_near(scene.camera.look_at->look_at, {-1, 0, 4});
    expect_near(scene.camera.look_at->up, {0, 1, 0});
    EXPECT_NEAR(scene.camera.look_at->fov_degrees, 0.5 * 180 / 3.14159265358979, 1e-4);
    EXPECT_EQ(loaded.settings.height, loaded.settings.width / 2);
    ASSERT_EQ(scene.lights.size(), 3u);  // the file's lights replace the automatic ones

    // Without a camera, the automatic framing looks at the model from +z.
    f.doc["scenes"][0]["nodes"] = {0};
    f.save(dir.path / "m.gltf");
    const Scene framed = make_quicklook_scene(dir.path / "m.gltf", diag).scene;
    EXPECT_GT(framed.camera.look_at->origin.z, 1.0f);
    EXPECT_EQ(framed.lights.size(), 3u);
}

TEST(GltfLoader, DracoBunnyHasItsTriangles) {
    SOMBRA_REQUIRE_SHARED("models/gltf/bunny.glb");
    Diagnostics diag;
    const LoadedMesh m = load_mesh_file(testing::shared_dir() / "models/gltf/bunny.glb", diag);
    EXPECT_EQ(m.mesh.triangle_count(), 5648u);  // 16944 indices
    EXPECT_EQ(m.mesh.positions.size(), 2826u);
    EXPECT_TRUE(m.mesh.has_normals());
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].type, MaterialType::Pbr);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
}

}  // namespace
}  // namespace sombra
