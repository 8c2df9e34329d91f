// glTF vertex attributes at a hit (spec §12, §13): COLOR_0 multiplies the
// base colour (factor × colour × texture); TANGENT gives the normal map its
// frame, also under mirroring nodes and scene transforms; normalTexture's
// scale flattens or steepens the mapped normal as glTF's formula says. Each
// on a 2×2 quad in z = 0 facing +z, loaded through a scene file and hit
// straight down from +z.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "io/gltf/gltf_test_files.h"
#include "io/images/image_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/interaction.h"
#include "render/shading.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

// Corners (−1, −1), (1, −1), (1, 1), (−1, 1), counter-clockwise from +z, with
// glTF uvs putting sombra's (u, v) at ((x + 1)/2, (y + 1)/2): the uv
// parameterisation's tangent is +x, its bitangent +y.
const std::vector<Vec3> kCorners{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};

// The quad with `material` (images 0 base.png, 1 n.png as textures 0 and 1),
// the attributes `add` writes (names → accessors), placed by node `node`.
template <class AddAttributes>
GltfFile shading_quad(const nlohmann::json& material, AddAttributes add,
                      nlohmann::json node = nlohmann::json::object()) {
    GltfFile f;
    nlohmann::json attributes = add(f);
    attributes["POSITION"] = f.add_positions(kCorners);
    attributes["NORMAL"] = f.add_normals(std::vector<Vec3>(4, Vec3{0, 0, 1}));
    attributes["TEXCOORD_0"] = f.add_uvs({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    f.add_mesh(attributes, f.add_indices({0, 1, 2, 0, 2, 3}), 0);
    f.doc["materials"] = {material};
    f.doc["images"] = {{{"uri", "base.png"}}, {{"uri", "n.png"}}};
    f.doc["textures"] = {{{"source", 0}}, {{"source", 1}}};
    node["mesh"] = 0;
    f.add_node(node);
    f.set_scene({0});
    return f;
}
nlohmann::json no_attributes(GltfFile&) { return nlohmann::json::object(); }

// The tangent-space normal (0.36, −0.48, 0.8) as a 16-bit texel, and what
// the renderer decodes from it (2·code/65535 − 1 per channel, not normalised).
// NOLINTNEXTLINE(bugprone-incorrect-roundings): constexpr, which std::lround is not; n >= -1, so never negative
constexpr std::uint16_t code(float n) { return static_cast<std::uint16_t>((n + 1) * 0.5f * 65535 + 0.5f); }
Vec3 decoded_texel() {
    const auto back = [](float n) { return 2 * static_cast<float>(code(n)) / 65535 - 1; };
    return Vec3{back(0.36f), back(-0.48f), back(0.8f)};
}

class GltfShading : public ::testing::Test {
protected:
    void SetUp() override {
        testing::write_png_file(dir.path / "base.png", 1, 1, 3, 8, {200, 100, 255});
        testing::write_png_file(dir.path / "n.png", 1, 1, 3, 16, {code(0.36f), code(-0.48f), code(0.8f)});
    }
    // The scene of `file` placed by `object_extra` (e.g. a transform), with the
    // scene's own material "grey" (diffuse) available for overrides.
    Scene load(const GltfFile& file, const std::string& object_extra = "") {
        file.save(dir.path / "q.gltf");
        dir.write("s.json", R"({"camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]},
            "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}},
            "objects": [{"file": "q.gltf")" +
                                object_extra + "}]}");
        Diagnostics diag;
        return load_scene_file(dir.path / "s.json", diag).scene;
    }
    TempFolder dir;
};

// The interaction where a ray straight down from above (x, y) meets the scene.
SurfaceInteraction hit_from_above(const Scene& scene, const Accel& accel, float x, float y) {
    const Ray ray{{x, y, 4}, {0, 0, -1}};
    Hit hit;
    EXPECT_TRUE(intersect(accel, ray, hit)) << "no hit at (" << x << ", " << y << ")";
    return make_surface_interaction(scene.geometry, ray, hit);
}

void expect_near(Vec3 got, Vec3 want, float tolerance, const std::string& what) {
    EXPECT_NEAR(got.x, want.x, tolerance) << what;
    EXPECT_NEAR(got.y, want.y, tolerance) << what;
    EXPECT_NEAR(got.z, want.z, tolerance) << what;
}

const Vec2 kPoints[] = {{-0.6f, -0.7f}, {0.5f, -0.2f}, {0.3f, 0.8f}, {-0.75f, 0.4f}, {0.0f, 0.0f}};

// Colours affine in (x, y) at the corners: linear interpolation over either
// triangle reproduces the affine function anywhere, R = (100 + 50x)/255,
// G = (120 + 40y)/255, B = 200/255, as unsigned bytes (A 255).
const std::vector<std::uint8_t> kCornerBytes{50,  80,  200, 255, 150, 80,  200, 255,
                                             150, 160, 200, 255, 50,  160, 200, 255};
Vec3 affine_colour(Vec2 p) { return Vec3{100 + 50 * p.x, 120 + 40 * p.y, 200} / 255.0f; }

TEST_F(GltfShading, VertexColoursMultiplyBaseColourFactorAndTexture) {
    const nlohmann::json material = {
        {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.8, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}};
    Scene scene = load(shading_quad(material, [](GltfFile& f) {
        return nlohmann::json{{"COLOR_0", f.add_array(kCornerBytes, gltf_test::kUnsignedByte, 4, "VEC4", true)}};
    }));
    const Accel accel = make_accel(scene.geometry, AccelKind::Bvh);
    const Vec3 texel{srgb_decode(200, 255), srgb_decode(100, 255), srgb_decode(255, 255)};
    for (const Vec2 p : kPoints) {
        SurfaceInteraction si = hit_from_above(scene, accel, p.x, p.y);
        EXPECT_TRUE(needs_resolved_material(scene, si));
        Material scratch;
        const Material& m = resolve_material(scene, si, scratch);
        expect_near(m.base_color, Vec3{0.5f, 0.8f, 1.0f} * affine_colour(p) * texel, 1e-6f,
                    "at (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")");
    }
}

TEST_F(GltfShading, VertexColoursAloneMakeAHitResolveAndOnlyForPbr) {
    std::vector<Vec3> floats;
    for (const Vec3 c : kCorners) floats.push_back(affine_colour({c.x, c.y}));
    const auto coloured = [&](GltfFile& f) {
        return nlohmann::json{{"COLOR_0", f.add_array(floats, gltf_test::kFloat, 4, "VEC3")}};
    };
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.8, 1.0, 1.0}}}}};
    Scene scene = load(shading_quad(material, coloured));
    const Accel accel = make_accel(scene.geometry, AccelKind::Bvh);
    ASSERT_FALSE(scene.materials[0].textured);
    for (const Vec2 p : kPoints) {
        SurfaceInteraction si = hit_from_above(scene, accel, p.x, p.y);
        EXPECT_TRUE(needs_resolved_material(scene, si));
        Material scratch;
        const Material& m = resolve_material(scene, si, scratch);
        EXPECT_EQ(&m, &scratch);
        expect_near(m.base_color, Vec3{0.5f, 0.8f, 1.0f} * affine_colour(p), 1e-6f, "untextured, coloured");
    }

    // The same quad without colours: the material itself, untouched.
    Scene plain = load(shading_quad(material, no_attributes));
    const Accel plain_accel = make_accel(plain.geometry, AccelKind::Bvh);
    SurfaceInteraction si = hit_from_above(plain, plain_accel, 0.2f, 0.3f);
    // needs_resolved_material says so beforehand, so that the direct
    // integrator can skip making a scratch Material.
    EXPECT_FALSE(needs_resolved_material(plain, si));
    Material scratch;
    EXPECT_EQ(&resolve_material(plain, si, scratch), &plain.materials[si.material]);

    // A scene's diffuse material in place of the file's: colours are the pbr base colour's, not kd's.
    Scene overridden = load(shading_quad(material, coloured), R"(, "material": "grey")");
    const Accel overridden_accel = make_accel(overridden.geometry, AccelKind::Bvh);
    SurfaceInteraction grey = hit_from_above(overridden, overridden_accel, 0.2f, 0.3f);
    EXPECT_FALSE(needs_resolved_material(overridden, grey));
    EXPECT_EQ(&resolve_material(overridden, grey, scratch), &overridden.materials[grey.material]);
}

// The normal map's texel in the frame t, w·(n × t), n with n = +z.
Vec3 in_frame(Vec3 t, float w) {
    const Vec3 n{0, 0, 1}, m = normalize(decoded_texel());
    return normalize(m.x * t + m.y * w * cross(n, t) + m.z * n);
}

const nlohmann::json kNormalMapped = {{"normalTexture", {{"index", 1}}}};

// File tangents along +y: turned a quarter against the uvs' +x.
GltfFile tangent_quad(float handedness, nlohmann::json node = nlohmann::json::object()) {
    return shading_quad(
        kNormalMapped,
        [=](GltfFile& f) {
            const std::vector<float> t{0, 1, 0, handedness, 0, 1, 0, handedness,
                                       0, 1, 0, handedness, 0, 1, 0, handedness};
            return nlohmann::json{{"TANGENT", f.add_array(t, gltf_test::kFloat, 4, "VEC4")}};
        },
        std::move(node));
}

Vec3 shading_normal_at(const Scene& scene, Vec2 p) {
    const Accel accel = make_accel(scene.geometry, AccelKind::Bvh);
    SurfaceInteraction si = hit_from_above(scene, accel, p.x, p.y);
    Material scratch;
    resolve_material(scene, si, scratch);
    return si.n_s;
}

TEST_F(GltfShading, FileTangentsGiveTheNormalMapItsFrame) {
    const Vec3 m = normalize(decoded_texel());
    // Without tangents, the uv frame (+x, +y): the texel as it is.
    expect_near(shading_normal_at(load(shading_quad(kNormalMapped, no_attributes)), {0.3f, -0.4f}), m, 1e-6f,
                "uv frame");
    // t = +y, n × t = −x: w = +1 gives (−m.y, m.x, m.z) = (0.48, 0.36, 0.8), w = −1 (m.y, m.x, m.z).
    for (const float w : {1.0f, -1.0f}) {
        const Vec3 want{-w * m.y, m.x, m.z};
        expect_near(in_frame({0, 1, 0}, w), want, 1e-6f, "the prediction itself");
        for (const Vec2 p : kPoints)
            expect_near(shading_normal_at(load(tangent_quad(w)), p), want, 1e-5f, "handedness " + std::to_string(w));
    }
}

TEST_F(GltfShading, MirroredTangentFramesShadeAsTheMirrorImage) {
    // Mirrored in x (by a node, or by the scene's transform), the bumps are
    // mirrored: the normal is the unmirrored one with x negated,
    // (m.y, m.x, m.z) for w = +1; a handedness left unflipped would give
    // (−m.y, m.x, m.z), the uv frame (−m.x, m.y, m.z).
    const Vec3 m = normalize(decoded_texel());
    const Vec3 want{m.y, m.x, m.z};
    for (const Vec2 p : kPoints) {
        expect_near(shading_normal_at(load(tangent_quad(1, {{"scale", {-1, 1, 1}}})), p), want, 1e-5f, "node mirror");
        expect_near(shading_normal_at(load(tangent_quad(1), R"(, "transform": [{"scale": [-1, 1, 1]}])"), p), want,
                    1e-5f, "scene mirror");
        // Both mirrors at once cancel.
        expect_near(shading_normal_at(
                        load(tangent_quad(1, {{"scale", {-1, 1, 1}}}), R"(, "transform": [{"scale": [-1, 1, 1]}])"), p),
                    Vec3{-m.y, m.x, m.z}, 1e-5f, "two mirrors");
    }
}

TEST_F(GltfShading, NormalTextureScaleFollowsGltfsFormula) {
    const Vec3 texel = decoded_texel();
    for (const float scale : {0.0f, 0.5f, 2.0f}) {
        nlohmann::json material = kNormalMapped;
        material["normalTexture"]["scale"] = scale;
        // normalize((2·sample − 1) ⊙ (scale, scale, 1)), in the uv frame (world axes here).
        const Vec3 want = normalize(Vec3{texel.x * scale, texel.y * scale, texel.z});
        if (scale == 0.0f) expect_near(want, {0, 0, 1}, 0.0f, "scale 0 is the unperturbed normal");
        expect_near(shading_normal_at(load(shading_quad(material, no_attributes)), {0.3f, -0.4f}), want, 1e-6f,
                    "scale " + std::to_string(scale));
    }
}

}  // namespace
}  // namespace sombra
