// glTF TANGENT and COLOR_0 (spec §12, §13) from tiny files written here:
// each corner keeps its own vertex's value through node transforms, mirrors
// (winding swapped, handedness flipped), a scene file's object transform,
// and Draco compression; the accessor types glTF allows; broken values.
#include <gtest/gtest.h>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <cmath>
#include <map>
#include <utility>

#include "io/gltf/gltf_test_files.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

const std::vector<Vec3> kCorners{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<std::uint32_t> kQuadIndices{0, 1, 2, 0, 2, 3};

LoadedMesh load(const GltfFile& f, Diagnostics& diag, const char* name = "m.gltf") {
    TempFolder dir;
    f.save(dir.path / name);
    return load_mesh_file(dir.path / name, diag);
}

// The unit quad of kCorners (facing +z, counter-clockwise) with normals and
// the attributes `add` writes into the file (it returns their names →
// accessors), placed by one node `node`.
template <class AddAttributes>
GltfFile quad_with(AddAttributes add, nlohmann::json node = nlohmann::json::object()) {
    GltfFile f;
    nlohmann::json attributes = add(f);
    attributes["POSITION"] = f.add_positions(kCorners);
    attributes["NORMAL"] = f.add_normals(std::vector<Vec3>(4, Vec3{0, 0, 1}));
    f.add_mesh(attributes, f.add_indices(kQuadIndices));
    node["mesh"] = 0;
    f.add_node(node);
    f.set_scene({0});
    return f;
}

// For every triangle corner of `m`, its position and its value of an
// attribute (by `value_of(triangle, corner)`), each position checked to
// carry the same value wherever it appears.
template <class T, class ValueOf>
std::map<std::array<float, 3>, T> value_by_position(const TriangleMesh& m, ValueOf value_of) {
    std::map<std::array<float, 3>, T> out;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) {
            const Vec3 p = m.positions[m.triangles[t][c]];
            const T v = value_of(t, c);
            const auto [it, is_new] = out.try_emplace({p.x, p.y, p.z}, v);
            EXPECT_TRUE(is_new || it->second == v) << "a vertex with two values at (" << p.x << ", " << p.y << ")";
        }
    return out;
}

std::map<std::array<float, 3>, Rgba> colors_by_position(const TriangleMesh& m) {
    EXPECT_TRUE(m.has_colors());
    return value_by_position<Rgba>(m, [&](std::size_t t, int c) { return m.colors[m.color_indices[t][c]]; });
}

std::map<std::array<float, 3>, std::array<float, 4>> tangents_by_position(const TriangleMesh& m) {
    EXPECT_TRUE(m.has_tangents());
    return value_by_position<std::array<float, 4>>(m, [&](std::size_t t, int c) {
        const VertexTangent v = m.tangents[m.tangent_indices[t][c]];
        return std::array<float, 4>{v.direction.x, v.direction.y, v.direction.z, v.handedness};
    });
}

void expect_near(const std::array<float, 4>& got, const std::array<float, 4>& want, const std::string& what) {
    for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(got[k], want[k], 1e-6f) << what << ", component " << k;
}

TEST(GltfAttributes, Vec3FloatColoursGetAlphaOne) {
    const std::vector<Vec3> rgb{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.25f, 0.5f, 0.75f}};
    Diagnostics diag;
    const LoadedMesh m = load(quad_with([&](GltfFile& f) {
                                  return nlohmann::json{{"COLOR_0", f.add_array(rgb, gltf_test::kFloat, 4, "VEC3")}};
                              }),
                              diag);
    const auto by_position = colors_by_position(m.mesh);
    for (std::size_t i = 0; i < 4; ++i)
        EXPECT_EQ(by_position.at({kCorners[i].x, kCorners[i].y, kCorners[i].z}),
                  (Rgba{rgb[i].x, rgb[i].y, rgb[i].z, 1.0f}));
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
}

TEST(GltfAttributes, NormalisedUnsignedColoursAreScaledToOne) {
    const std::vector<std::uint8_t> bytes{255, 0, 51, 255, 0, 255, 0, 128, 0, 0, 255, 0, 102, 204, 153, 51};
    const std::vector<std::uint16_t> shorts{65535, 0, 13107, 0, 65535, 0, 0, 65535, 0, 26214, 52428, 39321};
    Diagnostics diag;
    const LoadedMesh a =
        load(quad_with([&](GltfFile& f) {
                 return nlohmann::json{{"COLOR_0", f.add_array(bytes, gltf_test::kUnsignedByte, 4, "VEC4", true)}};
             }),
             diag);
    const LoadedMesh b =
        load(quad_with([&](GltfFile& f) {
                 return nlohmann::json{{"COLOR_0", f.add_array(shorts, gltf_test::kUnsignedShort, 4, "VEC3", true)}};
             }),
             diag);
    const auto bytes_at = colors_by_position(a.mesh), shorts_at = colors_by_position(b.mesh);
    for (std::size_t i = 0; i < 4; ++i) {
        const std::array<float, 3> p{kCorners[i].x, kCorners[i].y, kCorners[i].z};
        for (std::size_t c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(bytes_at.at(p)[c], bytes[4 * i + c] / 255.0f);
        for (std::size_t c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(shorts_at.at(p)[c], shorts[3 * i + c] / 65535.0f);
        EXPECT_EQ(shorts_at.at(p)[3], 1.0f);
    }
    // Integers that are not normalised are no colours in glTF.
    EXPECT_THROW(load(quad_with([&](GltfFile& f) {
                          return nlohmann::json{{"COLOR_0", f.add_array(bytes, gltf_test::kUnsignedByte, 4, "VEC4")}};
                      }),
                      diag),
                 Error);
}

TEST(GltfAttributes, FloatColoursOutsideTheUnitRangeAreClampedWithAWarning) {
    const std::vector<float> rgba{1.5f, -0.5f, 0.5f, 1, 0, 0, 0, 2, 1, 1, 1, 1, 0.5f, 0.5f, 0.5f, 0.5f};
    Diagnostics diag;
    const LoadedMesh m = load(quad_with([&](GltfFile& f) {
                                  return nlohmann::json{{"COLOR_0", f.add_array(rgba, gltf_test::kFloat, 4, "VEC4")}};
                              }),
                              diag);
    EXPECT_EQ(colors_by_position(m.mesh).at({0, 0, 0}), (Rgba{1, 0, 0.5f, 1}));
    EXPECT_EQ(colors_by_position(m.mesh).at({1, 0, 0}), (Rgba{0, 0, 0, 1}));
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("COLOR_0: 3 components outside [0, 1] clamped"), std::string::npos)
        << diag.warnings[0];
}

// Tangents (x, y, z, w) per corner of kCorners: lengths other than 1 and both handednesses.
const std::vector<float> kTangents{2, 0, 0, 1, 0, 3, 0, -1, 0.6f, 0.8f, 0, 1, 0, 0, -0.5f, -1};

GltfFile tangent_quad(nlohmann::json node = nlohmann::json::object()) {
    return quad_with(
        [](GltfFile& f) {
            return nlohmann::json{{"TANGENT", f.add_array(kTangents, gltf_test::kFloat, 4, "VEC4")}};
        },
        std::move(node));
}

TEST(GltfAttributes, TangentsAreNormalisedAndKeepTheirHandedness) {
    Diagnostics diag;
    const auto by_position = tangents_by_position(load(tangent_quad(), diag).mesh);
    expect_near(by_position.at({0, 0, 0}), {1, 0, 0, 1}, "corner 0");
    expect_near(by_position.at({1, 0, 0}), {0, 1, 0, -1}, "corner 1");
    expect_near(by_position.at({1, 1, 0}), {0.6f, 0.8f, 0, 1}, "corner 2");
    expect_near(by_position.at({0, 1, 0}), {0, 0, -1, -1}, "corner 3");
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
}

TEST(GltfAttributes, NodeTransformsTurnTangentsAndMirrorsFlipTheirHandedness) {
    Diagnostics diag;
    // 90° about +z: x → y, y → −x; a direction, so the translation does not move it.
    const float h = std::sqrt(0.5f);
    const auto turned = tangents_by_position(
        load(tangent_quad({{"rotation", {0, 0, h, h}}, {"translation", {5, 0, 0}}, {"scale", {2, 2, 2}}}), diag).mesh);
    expect_near(turned.at({5, 0, 0}), {0, 1, 0, 1}, "corner 0 turned");
    expect_near(turned.at({5, 2, 0}), {-1, 0, 0, -1}, "corner 1 turned");
    expect_near(turned.at({3, 2, 0}), {-0.8f, 0.6f, 0, 1}, "corner 2 turned");

    // Mirrored in x: directions mirrored, every handedness flipped, and each
    // corner still carries its own vertex's tangent after the winding swap.
    const TriangleMesh mirrored = load(tangent_quad({{"scale", {-1, 1, 1}}}), diag).mesh;
    const auto by_position = tangents_by_position(mirrored);
    expect_near(by_position.at({0, 0, 0}), {-1, 0, 0, -1}, "corner 0 mirrored");
    expect_near(by_position.at({-1, 0, 0}), {0, 1, 0, 1}, "corner 1 mirrored");
    expect_near(by_position.at({-1, 1, 0}), {-0.6f, 0.8f, 0, -1}, "corner 2 mirrored");
    expect_near(by_position.at({0, 1, 0}), {0, 0, -1, 1}, "corner 3 mirrored");
    for (const Index3& t : mirrored.triangles)
        EXPECT_GT(testing::twice_area_along(mirrored.positions[t[0]], mirrored.positions[t[1]],
                                            mirrored.positions[t[2]], {0, 0, 1}),
                  0);
}

TEST(GltfAttributes, ASceneObjectsMirrorFlipsTangentsAsANodesDoes) {
    TempFolder dir;
    tangent_quad().save(dir.path / "m.gltf");
    dir.write("s.json", R"({"camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]},
        "objects": [{"file": "m.gltf", "transform": [{"scale": [1, -2, 1]}, {"translate": [0, 0, 1]}]}]})");
    Diagnostics diag;
    const Scene scene = load_scene_file(dir.path / "s.json", diag).scene;
    const auto by_position = tangents_by_position(scene.geometry);
    expect_near(by_position.at({0, 0, 1}), {1, 0, 0, -1}, "corner 0");
    expect_near(by_position.at({1, 0, 1}), {0, -1, 0, 1}, "corner 1");
    // (0.6, 0.8) scaled to (0.6, −1.6), then renormalised.
    const float len = std::sqrt(0.36f + 2.56f);
    expect_near(by_position.at({1, -2, 1}), {0.6f / len, -1.6f / len, 0, -1}, "corner 2");
}

TEST(GltfAttributes, ZeroTangentsAreDroppedWithAWarningAndNonFiniteOnesAreAnError) {
    std::vector<float> tangents = kTangents;
    tangents[0] = 0;  // corner 0: (0, 0, 0)
    Diagnostics diag;
    const TriangleMesh m =
        load(quad_with([&](GltfFile& f) {
                 return nlohmann::json{{"TANGENT", f.add_array(tangents, gltf_test::kFloat, 4, "VEC4")}};
             }),
             diag)
            .mesh;
    ASSERT_TRUE(m.has_tangents());
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(m.tangent_indices[t][c] == kNoTangent, m.positions[m.triangles[t][c]] == (Vec3{0, 0, 0}));
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("1 tangent of zero length or not finite ignored"), std::string::npos)
        << diag.warnings[0];

    tangents[0] = std::nanf("");
    try {
        load(quad_with([&](GltfFile& f) {
                 return nlohmann::json{{"TANGENT", f.add_array(tangents, gltf_test::kFloat, 4, "VEC4")}};
             }),
             diag);
        ADD_FAILURE() << "a NaN tangent loaded";
    } catch (const Error& e) {
        EXPECT_NE(e.message().find("(TANGENT of mesh 0 primitive 0): element 0 is not finite"), std::string::npos)
            << e.message();
    }
}

// The quad compressed with Draco: positions, a float GENERIC attribute for
// TANGENT, COLOR_0 as unsigned bytes (`normalized` as Draco records it), and
// a TEX_COORD attribute the primitive maps as TEXCOORD_1 (spec §24).
GltfFile draco_quad(bool colour_marked_normalised) {
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int tangent = builder.AddAttribute(draco::GeometryAttribute::GENERIC, 4, draco::DT_FLOAT32);
    const int colour =
        builder.AddAttribute(draco::GeometryAttribute::COLOR, 3, draco::DT_UINT8, colour_marked_normalised);
    const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    const std::uint8_t rgb[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {51, 102, 153}};
    const float uvs[4][2] = {{0.5f, 0.25f}, {2, 0.25f}, {2, 1}, {0.5f, 1}};
    for (int face = 0; face < 2; ++face) {
        const std::uint32_t* c = kQuadIndices.data() + 3 * face;
        builder.SetAttributeValuesForFace(position, draco::FaceIndex(face), &kCorners[c[0]], &kCorners[c[1]],
                                          &kCorners[c[2]]);
        builder.SetAttributeValuesForFace(tangent, draco::FaceIndex(face), &kTangents[4 * c[0]], &kTangents[4 * c[1]],
                                          &kTangents[4 * c[2]]);
        builder.SetAttributeValuesForFace(colour, draco::FaceIndex(face), rgb[c[0]], rgb[c[1]], rgb[c[2]]);
        builder.SetAttributeValuesForFace(uv, draco::FaceIndex(face), uvs[c[0]], uvs[c[1]], uvs[c[2]]);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::EncoderBuffer encoded;
    draco::Encoder encoder;
    EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());

    GltfFile f;
    const int view = f.add_view(encoded.data(), encoded.size());
    f.doc["accessors"] = {
        {{"componentType", gltf_test::kFloat}, {"count", 4}, {"type", "VEC3"}},
        {{"componentType", gltf_test::kFloat}, {"count", 4}, {"type", "VEC4"}},
        {{"componentType", gltf_test::kUnsignedByte}, {"count", 4}, {"type", "VEC3"}, {"normalized", true}},
        {{"componentType", gltf_test::kUnsignedInt}, {"count", 6}, {"type", "SCALAR"}},
        {{"componentType", gltf_test::kFloat}, {"count", 4}, {"type", "VEC2"}}};
    f.doc["meshes"] = {{{"primitives",
                         {{{"attributes", {{"POSITION", 0}, {"TANGENT", 1}, {"COLOR_0", 2}, {"TEXCOORD_1", 4}}},
                           {"indices", 3},
                           {"extensions",
                            {{"KHR_draco_mesh_compression",
                              {{"bufferView", view},
                               {"attributes",
                                {{"POSITION", mesh->attribute(position)->unique_id()},
                                 {"TANGENT", mesh->attribute(tangent)->unique_id()},
                                 {"COLOR_0", mesh->attribute(colour)->unique_id()},
                                 {"TEXCOORD_1", mesh->attribute(uv)->unique_id()}}}}}}}}}}}};
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    f.use_extension("KHR_draco_mesh_compression", true);
    return f;
}

TEST(GltfAttributes, DracoCarriesTangentsColoursAndASecondUvSet) {
    for (const bool marked : {true, false}) {
        SCOPED_TRACE(marked ? "colours marked normalised" : "colours not marked normalised");
        Diagnostics diag;
        const TriangleMesh m = load(draco_quad(marked), diag, "d.glb").mesh;
        const auto tangents = tangents_by_position(m);
        expect_near(tangents.at({1, 0, 0}), {0, 1, 0, -1}, "corner 1");
        expect_near(tangents.at({0, 1, 0}), {0, 0, -1, -1}, "corner 3");
        const auto colours = colors_by_position(m);
        EXPECT_EQ(colours.at({0, 0, 0}), (Rgba{1, 0, 0, 1}));
        EXPECT_EQ(colours.at({0, 1, 0}), (Rgba{51 / 255.0f, 102 / 255.0f, 153 / 255.0f, 1}));
        // TEXCOORD_1 lands in the second set, v flipped; there is no set 0.
        EXPECT_FALSE(m.has_uvs());
        const UvSet& set1 = m.extra_uvs[0];
        ASSERT_EQ(set1.indices.size(), m.triangles.size());
        for (std::size_t t = 0; t < m.triangles.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                const Vec3 p = m.positions[m.triangles[t][std::size_t(k)]];
                const Vec2 uv = set1.uvs[set1.indices[t][std::size_t(k)]];
                EXPECT_EQ(uv.x, p.x == 0 ? 0.5f : 2.0f);
                EXPECT_EQ(uv.y, 1.0f - (p.y == 0 ? 0.25f : 1.0f));
            }
        EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
    }
}

}  // namespace
}  // namespace sombra
