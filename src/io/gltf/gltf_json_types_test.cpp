// glTF members of the wrong JSON type (spec §24): each is one Error whose
// WHERE is "FILE: /json/pointer" of the member and whose WHAT says what was
// expected and what the file has, never a model rendered without the member
// (tinygltf alone skips it). Extras, unknown members and unknown extensions
// stay allowed, and a valid file loads as before.
#include <gtest/gtest.h>

#include <functional>

#include "io/gltf/gltf_test_files.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using nlohmann::json;
using testing::TempFolder;

// A quad whose file holds most members sombra reads, each of its right type:
// a material with factors, textureInfo objects and extensions, a texture,
// sampler and image, a camera, a point light, a scene name.
GltfFile typed_quad() {
    GltfFile f = gltf_test::quad_file();
    f.doc["meshes"][0]["primitives"][0]["material"] = 0;
    f.doc["meshes"][0]["primitives"][0]["mode"] = 4;
    const json transform = {{"offset", {0, 0}}, {"rotation", 0}, {"scale", {1, 1}}};
    const json texture_info = {{"index", 0}, {"texCoord", 0}, {"extensions", {{"KHR_texture_transform", transform}}}};
    f.doc["materials"] = {{{"name", "m"},
                           {"pbrMetallicRoughness",
                            {{"baseColorFactor", {1, 1, 1, 1}},
                             {"baseColorTexture", texture_info},
                             {"metallicFactor", 0},
                             {"roughnessFactor", 0.5}}},
                           {"normalTexture", {{"index", 0}, {"scale", 1}}},
                           {"occlusionTexture", {{"index", 0}, {"strength", 1}}},
                           {"emissiveFactor", {0, 0, 0}},
                           {"alphaMode", "OPAQUE"},
                           {"alphaCutoff", 0.5},
                           {"doubleSided", false},
                           {"extensions",
                            {{"KHR_materials_ior", {{"ior", 1.5}}},
                             {"KHR_materials_emissive_strength", {{"emissiveStrength", 1}}},
                             {"KHR_materials_sheen",
                              {{"sheenColorFactor", {0.5, 0.5, 0.5}},
                               {"sheenRoughnessFactor", 0.5},
                               {"sheenColorTexture", texture_info},
                               {"sheenRoughnessTexture", {{"index", 0}}}}},
                             {"KHR_materials_clearcoat",
                              {{"clearcoatFactor", 1},
                               {"clearcoatTexture", texture_info},
                               {"clearcoatRoughnessFactor", 0.1},
                               {"clearcoatRoughnessTexture", {{"index", 0}}},
                               {"clearcoatNormalTexture", {{"index", 0}, {"texCoord", 0}, {"scale", 0.5}}}}}}}}};
    f.doc["textures"] = {{{"sampler", 0}, {"source", 0}}};
    f.doc["samplers"] = {{{"magFilter", 9729}, {"wrapS", 10497}, {"wrapT", 33071}}};
    f.doc["images"] = {{{"uri", "missing.png"}}};  // a warning: the constant is used
    f.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
    f.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1, 1, 1}}, {"intensity", 10}}};
    for (const char* name : {"KHR_texture_transform", "KHR_materials_ior", "KHR_materials_emissive_strength",
                             "KHR_materials_sheen", "KHR_materials_clearcoat", "KHR_lights_punctual"})
        f.use_extension(name);
    f.add_node(
        {{"name", "quad"}, {"mesh", 0}, {"translation", {0, 0, 0}}, {"rotation", {0, 0, 0, 1}}, {"scale", {1, 1, 1}}});
    f.add_node(
        {{"camera", 0}, {"translation", {0.5, 0.5, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    f.set_scene({0, 1});
    f.doc["scenes"][0]["name"] = "scene";
    return f;
}

json& primitive(GltfFile& f) { return f.doc["meshes"][0]["primitives"][0]; }
json& material(GltfFile& f) { return f.doc["materials"][0]; }

// Loads the file, expecting one Error; returns it (or an empty one).
Error load_error(const GltfFile& f, const std::string& name, const TempFolder& dir) {
    const std::filesystem::path path = dir.write(name, name.ends_with(".glb") ? f.glb() : f.gltf());
    Diagnostics diag;
    try {
        load_gltf(path, diag);
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << name << " loaded";
    return Error("", "");
}

struct WrongType {
    const char* name;
    std::function<void(GltfFile&)> damage;
    const char* pointer;
    const char* message;
    const char* file = "m.gltf";
};

const WrongType kWrongTypes[] = {
    // number
    {"a string for a scale", [](GltfFile& f) { f.doc["nodes"][0]["scale"] = "big"; }, "/nodes/0/scale",
     "expected an array of 3 numbers, got a string"},
    {"a string in a scale", [](GltfFile& f) { f.doc["nodes"][0]["scale"][1] = "2"; }, "/nodes/0/scale/1",
     "expected a number, got a string"},
    {"a boolean alphaCutoff", [](GltfFile& f) { material(f)["alphaCutoff"] = true; }, "/materials/0/alphaCutoff",
     "expected a number, got true"},
    {"a null yfov", [](GltfFile& f) { f.doc["cameras"][0]["perspective"]["yfov"] = nullptr; },
     "/cameras/0/perspective/yfov", "expected a number, got null"},
    {"a string light intensity",
     [](GltfFile& f) { f.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = "bright"; },
     "/extensions/KHR_lights_punctual/lights/0/intensity", "expected a number, got a string"},
    {"a string ior", [](GltfFile& f) { material(f)["extensions"]["KHR_materials_ior"]["ior"] = "1.5"; },
     "/materials/0/extensions/KHR_materials_ior/ior", "expected a number, got a string"},
    {"a string sheenRoughnessFactor",
     [](GltfFile& f) { material(f)["extensions"]["KHR_materials_sheen"]["sheenRoughnessFactor"] = "0.5"; },
     "/materials/0/extensions/KHR_materials_sheen/sheenRoughnessFactor", "expected a number, got a string"},
    {"a null in sheenColorFactor",
     [](GltfFile& f) { material(f)["extensions"]["KHR_materials_sheen"]["sheenColorFactor"][2] = nullptr; },
     "/materials/0/extensions/KHR_materials_sheen/sheenColorFactor/2", "expected a number, got null"},
    {"a string clearcoatNormalTexture scale",
     [](GltfFile& f) {
         material(f)["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"]["scale"] = "0.5";
     },
     "/materials/0/extensions/KHR_materials_clearcoat/clearcoatNormalTexture/scale", "expected a number, got a string"},
    {"a negative clearcoatNormalTexture index",
     [](GltfFile& f) { material(f)["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"]["index"] = -1; },
     "/materials/0/extensions/KHR_materials_clearcoat/clearcoatNormalTexture/index",
     "expected a non-negative integer, got -1"},
    {"a string clearcoatNormalTexture texCoord",
     [](GltfFile& f) {
         material(f)["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"]["texCoord"] = "1";
     },
     "/materials/0/extensions/KHR_materials_clearcoat/clearcoatNormalTexture/texCoord",
     "expected a non-negative integer, got a string"},
    {"an array for clearcoatNormalTexture",
     [](GltfFile& f) {
         material(f)["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"] = json::array();
     },
     "/materials/0/extensions/KHR_materials_clearcoat/clearcoatNormalTexture", "expected an object, got an array"},
    // array
    {"a number for sheenColorFactor",
     [](GltfFile& f) { material(f)["extensions"]["KHR_materials_sheen"]["sheenColorFactor"] = 1; },
     "/materials/0/extensions/KHR_materials_sheen/sheenColorFactor", "expected an array of 3 numbers, got 1"},
    {"an object for primitives", [](GltfFile& f) { f.doc["meshes"][0]["primitives"] = primitive(f); },
     "/meshes/0/primitives", "expected an array of objects, got an object"},
    {"a number for children", [](GltfFile& f) { f.doc["nodes"][0]["children"] = 1; }, "/nodes/0/children",
     "expected an array of non-negative integers, got 1"},
    {"a string for extensionsUsed", [](GltfFile& f) { f.doc["extensionsUsed"] = "KHR_lights_punctual"; },
     "/extensionsUsed", "expected an array of strings, got a string"},
    {"a string for a texture transform's offset",
     [](GltfFile& f) {
         material(f)["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"]["offset"] =
             "0 0";
     },
     "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/offset",
     "expected an array of 2 numbers, got a string"},
    // object
    {"an array for pbrMetallicRoughness", [](GltfFile& f) { material(f)["pbrMetallicRoughness"] = {"not an object"}; },
     "/materials/0/pbrMetallicRoughness", "expected an object, got an array"},
    {"a string for a texture transform",
     [](GltfFile& f) {
         material(f)["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = "x";
     },
     "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform",
     "expected an object, got a string"},
    {"a string for the asset", [](GltfFile& f) { f.doc["asset"] = "2.0"; }, "/asset",
     "expected an object, got a string"},
    {"a number for a primitive's extensions", [](GltfFile& f) { primitive(f)["extensions"] = 7; },
     "/meshes/0/primitives/0/extensions", "expected an object, got 7"},
    {"an array for sheenColorTexture",
     [](GltfFile& f) { material(f)["extensions"]["KHR_materials_sheen"]["sheenColorTexture"] = {0}; },
     "/materials/0/extensions/KHR_materials_sheen/sheenColorTexture", "expected an object, got an array"},
    // string
    {"a number for a scene's name", [](GltfFile& f) { f.doc["scenes"][0]["name"] = 42; }, "/scenes/0/name",
     "expected a string, got 42"},
    {"a number for an accessor's type", [](GltfFile& f) { f.doc["accessors"][0]["type"] = 3; }, "/accessors/0/type",
     "expected a string, got 3"},
    {"an array for alphaMode", [](GltfFile& f) { material(f)["alphaMode"] = {"MASK"}; }, "/materials/0/alphaMode",
     "expected a string, got an array"},
    // uint
    {"a negative texture index",
     [](GltfFile& f) { material(f)["pbrMetallicRoughness"]["baseColorTexture"]["index"] = -1; },
     "/materials/0/pbrMetallicRoughness/baseColorTexture/index", "expected a non-negative integer, got -1"},
    {"a negative sheenRoughnessTexture index",
     [](GltfFile& f) { material(f)["extensions"]["KHR_materials_sheen"]["sheenRoughnessTexture"]["index"] = -2; },
     "/materials/0/extensions/KHR_materials_sheen/sheenRoughnessTexture/index",
     "expected a non-negative integer, got -2"},
    {"a fraction for indices", [](GltfFile& f) { primitive(f)["indices"] = 1.5; }, "/meshes/0/primitives/0/indices",
     "expected a non-negative integer, got 1.5"},
    {"an integer written as a float", [](GltfFile& f) { f.doc["nodes"][0]["mesh"] = 0.0; }, "/nodes/0/mesh",
     "expected a non-negative integer, got 0.0"},
    {"a string count", [](GltfFile& f) { f.doc["accessors"][0]["count"] = "4"; }, "/accessors/0/count",
     "expected a non-negative integer, got a string"},
    {"an index beyond an int", [](GltfFile& f) { f.doc["scene"] = 4294967296u; }, "/scene",
     "4294967296 is too large (at most 2147483647)"},
    {"a string attribute", [](GltfFile& f) { primitive(f)["attributes"]["POSITION"] = "0"; },
     "/meshes/0/primitives/0/attributes/POSITION", "expected a non-negative integer, got a string"},
    {"an attribute whose name needs escaping", [](GltfFile& f) { primitive(f)["attributes"]["_A/B~"] = -2; },
     "/meshes/0/primitives/0/attributes/_A~1B~0", "expected a non-negative integer, got -2"},
    {"a negative light index",
     [](GltfFile& f) { f.doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = -1; },
     "/nodes/1/extensions/KHR_lights_punctual/light", "expected a non-negative integer, got -1"},
    {"a negative morph target accessor",
     [](GltfFile& f) {
         primitive(f)["targets"] = {{{"POSITION", -1}}};
     },
     "/meshes/0/primitives/0/targets/0/POSITION", "expected a non-negative integer, got -1"},
    // bool
    {"a string for doubleSided", [](GltfFile& f) { material(f)["doubleSided"] = "yes"; }, "/materials/0/doubleSided",
     "expected true or false, got a string"},
    {"a number for normalized", [](GltfFile& f) { f.doc["accessors"][0]["normalized"] = 0; }, "/accessors/0/normalized",
     "expected true or false, got 0"},
    // a GLB's JSON chunk is checked the same way
    {"a string for a scale, in a GLB", [](GltfFile& f) { f.doc["nodes"][0]["scale"] = "big"; }, "/nodes/0/scale",
     "expected an array of 3 numbers, got a string", "m.glb"},
};

TEST(GltfJsonTypes, TheTypedQuadLoads) {
    TempFolder dir;
    Diagnostics diag;
    const LoadedMesh m = load_gltf(dir.write("m.gltf", typed_quad().gltf()), diag);
    EXPECT_EQ(m.mesh.triangle_count(), 2u);
    EXPECT_EQ(m.lights.size(), 1u);
    EXPECT_TRUE(m.camera.has_value());
}

TEST(GltfJsonTypes, EachWrongTypeIsOneErrorNamingTheMember) {
    for (const WrongType& w : kWrongTypes) {
        SCOPED_TRACE(w.name);
        GltfFile f = typed_quad();
        w.damage(f);
        TempFolder dir;
        const Error e = load_error(f, w.file, dir);
        EXPECT_EQ(e.where(), (dir.path / w.file).string() + ": " + w.pointer);
        EXPECT_EQ(e.message(), w.message);
    }
}

// glTF allows extras and members it does not define, and extensions are
// free to use theirs; emissiveFactor's null entries read as 0 (spec §24).
TEST(GltfJsonTypes, ExtrasUnknownMembersAndUnknownExtensionsLoadUnchanged) {
    GltfFile f = typed_quad();
    f.doc["extras"] = "anything";
    f.doc["nodes"][0]["extras"] = {{"scale", "not checked"}};
    f.doc["nodes"][0]["futureMember"] = {1, "two"};
    f.doc["nodes"][0]["extensions"]["EXT_not_known"] = 3;
    f.doc["extensions"]["EXT_not_known"] = "x";
    f.use_extension("EXT_not_known");
    material(f)["emissiveFactor"] = {0, nullptr, 0};
    TempFolder dir;
    Diagnostics plain_diag, diag;
    const LoadedMesh plain = load_gltf(dir.write("plain.gltf", typed_quad().gltf()), plain_diag);
    const LoadedMesh m = load_gltf(dir.write("m.gltf", f.gltf()), diag);
    EXPECT_EQ(m.mesh.positions, plain.mesh.positions);
    EXPECT_EQ(m.mesh.triangles, plain.mesh.triangles);
    ASSERT_EQ(m.materials.size(), plain.materials.size());
    EXPECT_EQ(m.materials[0].base_color, plain.materials[0].base_color);
    EXPECT_EQ(m.materials[0].ke, plain.materials[0].ke);
    EXPECT_EQ(m.lights.size(), plain.lights.size());
}

// emissiveFactor is used as given, above 1 too; its null entries read as 0
// with one warning (obj2gltf writes them; tinygltf dropped the whole array).
TEST(GltfJsonTypes, EmissiveNullEntriesReadAsZeroWithOneWarning) {
    GltfFile f = typed_quad();
    material(f)["emissiveFactor"] = {2, nullptr, 0.5};
    TempFolder dir;
    Diagnostics diag;
    const LoadedMesh m = load_gltf(dir.write("m.gltf", f.gltf()), diag);
    EXPECT_EQ(m.materials[0].ke, (Vec3{2, 0, 0.5f}));
    std::size_t null_warnings = 0;
    for (const std::string& w : diag.warnings) null_warnings += w.find("null") != std::string::npos ? 1 : 0;
    EXPECT_EQ(null_warnings, 1u);
}

// KHR_materials_ior's ior = 1 is valid (f0 = 0), and so is 0 (f0 = 1: the
// specular-glossiness conversion of KHR_materials_specular); other values
// below 1 are outside its schema.
TEST(GltfJsonTypes, IorOfOneIsValid) {
    for (const double ior : {1.0, 0.0, 0.5}) {
        GltfFile f = typed_quad();
        material(f)["extensions"]["KHR_materials_ior"]["ior"] = ior;
        TempFolder dir;
        Diagnostics diag;
        const LoadedMesh m = load_gltf(dir.write("m.gltf", f.gltf()), diag);
        std::size_t ior_warnings = 0;
        for (const std::string& w : diag.warnings) ior_warnings += w.find("ior") != std::string::npos ? 1 : 0;
        const bool valid = ior != 0.5;
        EXPECT_EQ(m.materials[0].ior, valid ? static_cast<float>(ior) : 1.5f);
        EXPECT_EQ(ior_warnings, valid ? 0u : 1u);
    }
}

// An unsupported extension in extensionsRequired is named before any check
// its data would fail (spec §24); another glTF version is named as such.
TEST(GltfJsonTypes, RequiredExtensionsAndTheVersionComeFirst) {
    TempFolder dir;
    GltfFile f = typed_quad();
    f.use_extension("KHR_materials_anisotropy", true);
    f.doc["nodes"][0]["scale"] = "big";
    Error e = load_error(f, "required.gltf", dir);
    EXPECT_EQ(e.where(), (dir.path / "required.gltf").string());
    EXPECT_EQ(e.message(), "requires the unsupported glTF extension KHR_materials_anisotropy");

    GltfFile old = typed_quad();
    old.doc["asset"]["version"] = "1.0";
    old.doc["meshes"] = {{"mesh_0", old.doc["meshes"][0]}};  // glTF 1.0 keeps objects by name
    e = load_error(old, "old.gltf", dir);
    EXPECT_EQ(e.where(), (dir.path / "old.gltf").string());
    EXPECT_NE(e.message().find("version"), std::string::npos) << e.message();
}

// assimp's test models of wrong types (Debian's assimp-testmodels), each
// of which rendered without the member before.
TEST(GltfJsonTypes, AssimpWrongTypeModelsNameTheMember) {
    const std::filesystem::path root = "/usr/share/assimp/models/glTF2";
    if (!std::filesystem::is_directory(root / "wrongTypes"))
        GTEST_SKIP() << root / "wrongTypes"
                     << " not found (Debian package assimp-testmodels, tools/install-deps.sh)";
    const struct {
        const char* file;
        const char* pointer;
        const char* message;
    } cases[] = {
        {"wrongTypes/badArray.gltf", "/meshes/0/primitives", "expected an array of objects, got an object"},
        {"wrongTypes/badNumber.gltf", "/materials/0/normalTexture/scale", "expected a number, got a string"},
        {"wrongTypes/badObject.gltf", "/materials/0/pbrMetallicRoughness", "expected an object, got an array"},
        {"wrongTypes/badString.gltf", "/scenes/0/name", "expected a string, got 42"},
        {"wrongTypes/badUint.gltf", "/materials/0/pbrMetallicRoughness/baseColorTexture/index",
         "expected a non-negative integer, got -1"},
        {"wrongTypes/badExtension.gltf",
         "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform",
         "expected an object, got a string"},
        {"SchemaFailures/sceneWrongType.gltf", "/scene", "expected a non-negative integer, got a string"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.file);
        const std::filesystem::path path = root / c.file;
        Diagnostics diag;
        try {
            load_gltf(path, diag);
            ADD_FAILURE() << "loaded";
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), path.string() + ": " + c.pointer);
            EXPECT_EQ(e.message(), c.message);
        }
    }
}

}  // namespace
}  // namespace sombra
