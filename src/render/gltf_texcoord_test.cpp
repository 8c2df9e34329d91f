// glTF texture coordinate sets beyond TEXCOORD_0 (spec §24) through the
// whole pipeline: a file whose textures read TEXCOORD_1 renders bit for bit
// as the same file with the two sets swapped and the textures reading
// TEXCOORD_0, slot by slot (base colour, metallic-roughness, normal,
// emission, occlusion), each texture keeping its own set, with bilinear and
// mip-mapped lookups (the footprint is the set's), for a mesh drawn once
// and one drawn by two nodes (instanced), with the base colour's alpha as a
// cut-out, and with the textured emission lighting a floor (light sampling
// reads it too); a primitive without the set a texture reads shows the
// constant alone, with one warning.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/gltf/gltf_test_files.h"
#include "io/images/image_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

// glTF uvs of the quad's corners (−1, −1), (1, −1), (1, 1), (−1, 1): the
// plain map, and one mirrored in u, scaled and offset, so that its texels,
// its mip level and (without TANGENT) its normal map's frame all differ.
const std::vector<Vec2> kPlain{{0, 1}, {1, 1}, {1, 0}, {0, 0}};
std::vector<Vec2> other() {
    std::vector<Vec2> out;
    for (const Vec2 uv : kPlain) out.push_back({1.25f - 2 * uv.x, 0.5f + 1.5f * uv.y});
    return out;
}

const char* const kSlots[] = {"baseColorTexture", "metallicRoughnessTexture", "normalTexture", "emissiveTexture",
                              "occlusionTexture"};

// The textureInfo of `slot` in material `m`.
nlohmann::json& info(nlohmann::json& m, const std::string& slot) {
    if (slot == "baseColorTexture" || slot == "metallicRoughnessTexture") return m["pbrMetallicRoughness"][slot];
    return m[slot];
}

// The quad with TEXCOORD_0 = `set0` and TEXCOORD_1 = `set1` (none when
// empty), every slot textured from tex.png, `slot` reading set `slot_set`
// and the others set 1 − slot_set; drawn by one node, or by two (then an
// instanced mesh).
GltfFile quad(const std::vector<Vec2>& set0, const std::vector<Vec2>& set1, const std::string& slot, int slot_set,
              bool two_nodes, bool mask = false) {
    GltfFile f;
    nlohmann::json attributes = {{"POSITION", f.add_positions({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}})},
                                 {"NORMAL", f.add_normals(std::vector<Vec3>(4, Vec3{0, 0, 1}))},
                                 {"TEXCOORD_0", f.add_uvs(set0)}};
    if (!set1.empty()) attributes["TEXCOORD_1"] = f.add_uvs(set1);
    f.add_mesh(attributes, f.add_indices({0, 1, 2, 0, 2, 3}), 0);
    nlohmann::json m = {{"pbrMetallicRoughness", {{"metallicFactor", 0.8}, {"roughnessFactor", 0.9}}},
                        {"emissiveFactor", {0.3, 0.2, 0.1}}};
    for (const char* s : kSlots) info(m, s) = {{"index", 0}, {"texCoord", s == slot ? slot_set : 1 - slot_set}};
    if (mask) m["alphaMode"] = "MASK", m["alphaCutoff"] = 0.45;
    f.doc["materials"] = {m};
    f.doc["images"] = {{{"uri", "tex.png"}}};
    f.doc["textures"] = {{{"source", 0}}};
    if (two_nodes) {
        f.add_node({{"mesh", 0}, {"translation", {-0.55, 0, 0}}, {"scale", {0.5, 0.5, 0.5}}});
        f.add_node({{"mesh", 0}, {"translation", {0.55, 0, 0}}, {"scale", {0.5, 0.5, 0.5}}});
        f.set_scene({0, 1});
    } else {
        f.add_node({{"mesh", 0}});
        f.set_scene({0});
    }
    return f;
}

class GltfTexcoord : public ::testing::Test {
protected:
    void SetUp() override {
        // 8 × 8 RGBA, every texel and channel different.
        std::vector<std::uint16_t> texels;
        for (int j = 0; j < 8; ++j)
            for (int i = 0; i < 8; ++i)
                for (int c = 0; c < 4; ++c) texels.push_back(std::uint16_t((37 * i + 71 * j + 113 * c + 29) % 256));
        testing::write_png_file(dir.path / "tex.png", 8, 8, 4, 8, texels);
    }
    // `f` rendered, path-traced, over a floor that its emission lights too
    // (light sampling reads the texture), lit by a point light and seen at a
    // slant, with `filter`.
    Film render(const GltfFile& f, const std::string& filter, std::size_t* warnings = nullptr) {
        f.save(dir.path / "q.gltf");
        dir.write("floor.obj", "v -3 -1.2 -3\nv 3 -1.2 -3\nv 3 -1.2 3\nv -3 -1.2 3\nf 4 3 2 1\n");
        dir.write(
            "s.json",
            R"({"render": {"width": 32, "height": 24, "spp": 2, "integrator": "path", "max_depth": 2, "texture_filter": ")" +
                filter +
                R"("}, "camera": {"origin": [0.6, -0.8, 3], "look_at": [0, 0, 0], "fov": 50},
                "lights": [{"position": [1, 2, 3], "intensity": [20, 20, 20]}],
                "objects": [{"file": "q.gltf"}, {"file": "floor.obj"}]})");
        Diagnostics diag;
        const LoadedScene loaded = load_scene_file(dir.path / "s.json", diag);
        if (warnings) *warnings = diag.warnings.size();
        const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
        RenderProgress progress;
        return render_image(make_render_job(loaded.scene, accel, loaded.settings, 1), progress).film;
    }
    TempFolder dir;
};

TEST_F(GltfTexcoord, EachTextureReadsItsOwnSetBitForBit) {
    for (const bool two_nodes : {false, true})
        for (const bool mask : {false, true})
            for (const char* filter : {"bilinear", "mipmap"})
                for (const char* slot : kSlots) {
                    SCOPED_TRACE(std::string(slot) + ", " + filter + (two_nodes ? ", instanced" : "") +
                                 (mask ? ", cut out" : ""));
                    // `slot` reads the other map through TEXCOORD_1, the rest the
                    // plain map through TEXCOORD_0; then the sets swapped.
                    const Film a = render(quad(kPlain, other(), slot, 1, two_nodes, mask), filter);
                    const Film b = render(quad(other(), kPlain, slot, 0, two_nodes, mask), filter);
                    ASSERT_EQ(a.rgb.size(), b.rgb.size());
                    EXPECT_TRUE(a.rgb == b.rgb);
                    // Not vacuous: with every slot on the plain map the image
                    // differs (occlusion aside, which the renderer does not use).
                    if (std::string(slot) == "occlusionTexture") continue;
                    const Film plain = render(quad(kPlain, other(), slot, 0, two_nodes, mask), filter);
                    EXPECT_FALSE(a.rgb == plain.rgb);
                }
}

TEST_F(GltfTexcoord, AMissingSetLeavesTheConstantWithOneWarning) {
    // The base colour reads TEXCOORD_1, which the primitive lacks: as the
    // same material without a base colour texture. Every other slot on set 0.
    GltfFile missing = quad(kPlain, {}, "baseColorTexture", 1, false);
    for (const char* s : kSlots)
        if (std::string(s) != "baseColorTexture") info(missing.doc["materials"][0], s)["texCoord"] = 0;
    GltfFile without = missing;
    without.doc["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture");
    std::size_t warnings = 0, none = 0;
    const Film a = render(missing, "mipmap", &warnings);
    const Film b = render(without, "mipmap", &none);
    EXPECT_TRUE(a.rgb == b.rgb);
    EXPECT_EQ(warnings, none + 1);
}

}  // namespace
}  // namespace sombra
