// The glTF 2.0 schema's member types, as tables, and the walk that checks a
// document against them (spec §24). tinygltf skips a member whose type it
// does not expect as if it were absent, so without this a string for a
// scale, an array for a material's pbrMetallicRoughness or -1 for a texture
// index renders a different model instead of failing.
#include "io/gltf/gltf_json_types.h"

#include <nlohmann/json.hpp>

#include <climits>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "io/gltf/gltf.h"
#include "io/scene_json/scene_json.h"

namespace sombra::gltf {

namespace {

// What a member must be.
enum class Type {
    Number,
    Index,  // a non-negative integer that fits an int: tinygltf stores one, so more would wrap
    Size,   // a non-negative integer of up to 64 bits (byte offsets and lengths, counts)
    String,
    Bool,
    Object,         // an object whose members follow `shape`
    Objects,        // an array of such objects
    Numbers,        // an array of numbers
    NumbersOrNull,  // the same, null entries allowed (emissiveFactor: spec §24 reads null as 0)
    Indices,        // an array of Index
    Strings,        // an array of strings
};

struct Shape;

struct Member {
    std::string_view key;
    Type type;
    const Shape* shape = nullptr;  // Object and Objects
    int count = 0;                 // Numbers: the length the message names; 0 for any
};

// An object's known members, and what every other member must be when the
// keys are the file's own (attribute names); otherwise others go unchecked.
struct Shape {
    std::span<const Member> members;
    std::optional<Type> others = std::nullopt;
};

using T = Type;

// textureInfo (glTF 2.0 §5.22) and its two extended forms.
constexpr Member kTextureTransformMembers[] = {{"offset", T::Numbers, nullptr, 2},
                                               {"rotation", T::Number},
                                               {"scale", T::Numbers, nullptr, 2},
                                               {"texCoord", T::Index}};
constexpr Shape kTextureTransformShape{kTextureTransformMembers};
constexpr Member kTextureInfoExtensions[] = {{kTextureTransform, T::Object, &kTextureTransformShape}};
constexpr Shape kTextureInfoExtensionsShape{kTextureInfoExtensions};
constexpr Member kTextureInfo[] = {
    {"index", T::Index}, {"texCoord", T::Index}, {"extensions", T::Object, &kTextureInfoExtensionsShape}};
constexpr Shape kTextureInfoShape{kTextureInfo};
constexpr Member kNormalTextureInfo[] = {{"index", T::Index},
                                         {"texCoord", T::Index},
                                         {"scale", T::Number},
                                         {"extensions", T::Object, &kTextureInfoExtensionsShape}};
constexpr Shape kNormalTextureInfoShape{kNormalTextureInfo};
constexpr Member kOcclusionTextureInfo[] = {{"index", T::Index},
                                            {"texCoord", T::Index},
                                            {"strength", T::Number},
                                            {"extensions", T::Object, &kTextureInfoExtensionsShape}};
constexpr Shape kOcclusionTextureInfoShape{kOcclusionTextureInfo};

// material
constexpr Member kPbr[] = {{"baseColorFactor", T::Numbers, nullptr, 4},
                           {"baseColorTexture", T::Object, &kTextureInfoShape},
                           {"metallicFactor", T::Number},
                           {"roughnessFactor", T::Number},
                           {"metallicRoughnessTexture", T::Object, &kTextureInfoShape}};
constexpr Shape kPbrShape{kPbr};
constexpr Member kEmissiveStrengthMembers[] = {{"emissiveStrength", T::Number}};
constexpr Shape kEmissiveStrengthShape{kEmissiveStrengthMembers};
constexpr Member kIorMembers[] = {{"ior", T::Number}};
constexpr Shape kIorShape{kIorMembers};
constexpr Member kSheenMembers[] = {{"sheenColorFactor", T::Numbers, nullptr, 3},
                                    {"sheenColorTexture", T::Object, &kTextureInfoShape},
                                    {"sheenRoughnessFactor", T::Number},
                                    {"sheenRoughnessTexture", T::Object, &kTextureInfoShape}};
constexpr Shape kSheenShape{kSheenMembers};
constexpr Member kClearcoatMembers[] = {{"clearcoatFactor", T::Number},
                                        {"clearcoatTexture", T::Object, &kTextureInfoShape},
                                        {"clearcoatRoughnessFactor", T::Number},
                                        {"clearcoatRoughnessTexture", T::Object, &kTextureInfoShape},
                                        {"clearcoatNormalTexture", T::Object, &kNormalTextureInfoShape}};
constexpr Shape kClearcoatShape{kClearcoatMembers};
constexpr Member kMaterialExtensions[] = {{kEmissiveStrength, T::Object, &kEmissiveStrengthShape},
                                          {kIor, T::Object, &kIorShape},
                                          {kClearcoat, T::Object, &kClearcoatShape},
                                          {kSheen, T::Object, &kSheenShape}};
constexpr Shape kMaterialExtensionsShape{kMaterialExtensions};
constexpr Member kMaterial[] = {{"name", T::String},
                                {"pbrMetallicRoughness", T::Object, &kPbrShape},
                                {"normalTexture", T::Object, &kNormalTextureInfoShape},
                                {"occlusionTexture", T::Object, &kOcclusionTextureInfoShape},
                                {"emissiveTexture", T::Object, &kTextureInfoShape},
                                {"emissiveFactor", T::NumbersOrNull, nullptr, 3},
                                {"alphaMode", T::String},
                                {"alphaCutoff", T::Number},
                                {"doubleSided", T::Bool},
                                {"extensions", T::Object, &kMaterialExtensionsShape}};
constexpr Shape kMaterialShape{kMaterial};

// mesh and primitive; attribute maps name their own keys.
constexpr Shape kAttributesShape{{}, T::Index};
constexpr Member kDracoMembers[] = {{"bufferView", T::Index}, {"attributes", T::Object, &kAttributesShape}};
constexpr Shape kDracoShape{kDracoMembers};
constexpr Member kPrimitiveExtensions[] = {{kDraco, T::Object, &kDracoShape}};
constexpr Shape kPrimitiveExtensionsShape{kPrimitiveExtensions};
constexpr Member kPrimitive[] = {{"attributes", T::Object, &kAttributesShape},
                                 {"indices", T::Index},
                                 {"material", T::Index},
                                 {"mode", T::Index},
                                 {"targets", T::Objects, &kAttributesShape},
                                 {"extensions", T::Object, &kPrimitiveExtensionsShape}};
constexpr Shape kPrimitiveShape{kPrimitive};
constexpr Member kMesh[] = {{"name", T::String}, {"primitives", T::Objects, &kPrimitiveShape}, {"weights", T::Numbers}};
constexpr Shape kMeshShape{kMesh};

// node and scene
constexpr Member kNodeLight[] = {{"light", T::Index}};
constexpr Shape kNodeLightShape{kNodeLight};
constexpr Member kNodeExtensions[] = {{kLights, T::Object, &kNodeLightShape}};
constexpr Shape kNodeExtensionsShape{kNodeExtensions};
constexpr Member kNode[] = {{"name", T::String},
                            {"camera", T::Index},
                            {"children", T::Indices},
                            {"skin", T::Index},
                            {"matrix", T::Numbers, nullptr, 16},
                            {"mesh", T::Index},
                            {"rotation", T::Numbers, nullptr, 4},
                            {"scale", T::Numbers, nullptr, 3},
                            {"translation", T::Numbers, nullptr, 3},
                            {"weights", T::Numbers},
                            {"extensions", T::Object, &kNodeExtensionsShape}};
constexpr Shape kNodeShape{kNode};
constexpr Member kScene[] = {{"name", T::String}, {"nodes", T::Indices}};
constexpr Shape kSceneShape{kScene};

// accessor, buffer view, buffer
constexpr Member kSparseIndices[] = {{"bufferView", T::Index}, {"byteOffset", T::Size}, {"componentType", T::Index}};
constexpr Shape kSparseIndicesShape{kSparseIndices};
constexpr Member kSparseValues[] = {{"bufferView", T::Index}, {"byteOffset", T::Size}};
constexpr Shape kSparseValuesShape{kSparseValues};
constexpr Member kSparse[] = {{"count", T::Index},  // an int in tinygltf
                              {"indices", T::Object, &kSparseIndicesShape},
                              {"values", T::Object, &kSparseValuesShape}};
constexpr Shape kSparseShape{kSparse};
constexpr Member kAccessor[] = {{"name", T::String},     {"bufferView", T::Index},
                                {"byteOffset", T::Size}, {"componentType", T::Index},
                                {"normalized", T::Bool}, {"count", T::Size},
                                {"type", T::String},     {"max", T::Numbers},
                                {"min", T::Numbers},     {"sparse", T::Object, &kSparseShape}};
constexpr Shape kAccessorShape{kAccessor};
constexpr Member kMeshoptView[] = {{"buffer", T::Index},    {"byteOffset", T::Size}, {"byteLength", T::Size},
                                   {"byteStride", T::Size}, {"count", T::Size},      {"mode", T::String},
                                   {"filter", T::String}};
constexpr Shape kMeshoptViewShape{kMeshoptView};
constexpr Member kBufferViewExtensions[] = {{kMeshopt, T::Object, &kMeshoptViewShape}};
constexpr Shape kBufferViewExtensionsShape{kBufferViewExtensions};
constexpr Member kBufferView[] = {{"name", T::String},
                                  {"buffer", T::Index},
                                  {"byteOffset", T::Size},
                                  {"byteLength", T::Size},
                                  {"byteStride", T::Size},
                                  {"target", T::Index},
                                  {"extensions", T::Object, &kBufferViewExtensionsShape}};
constexpr Shape kBufferViewShape{kBufferView};
constexpr Member kMeshoptBuffer[] = {{"fallback", T::Bool}};
constexpr Shape kMeshoptBufferShape{kMeshoptBuffer};
constexpr Member kBufferExtensions[] = {{kMeshopt, T::Object, &kMeshoptBufferShape}};
constexpr Shape kBufferExtensionsShape{kBufferExtensions};
constexpr Member kBuffer[] = {{"name", T::String},
                              {"uri", T::String},
                              {"byteLength", T::Size},
                              {"extensions", T::Object, &kBufferExtensionsShape}};
constexpr Shape kBufferShape{kBuffer};

// texture, image, sampler
constexpr Member kWebpTexture[] = {{"source", T::Index}};
constexpr Shape kWebpTextureShape{kWebpTexture};
constexpr Member kTextureExtensions[] = {{kWebp, T::Object, &kWebpTextureShape}};
constexpr Shape kTextureExtensionsShape{kTextureExtensions};
constexpr Member kTexture[] = {{"name", T::String},
                               {"sampler", T::Index},
                               {"source", T::Index},
                               {"extensions", T::Object, &kTextureExtensionsShape}};
constexpr Shape kTextureShape{kTexture};
constexpr Member kImage[] = {
    {"name", T::String}, {"uri", T::String}, {"mimeType", T::String}, {"bufferView", T::Index}};
constexpr Shape kImageShape{kImage};
constexpr Member kSampler[] = {
    {"name", T::String}, {"magFilter", T::Index}, {"minFilter", T::Index}, {"wrapS", T::Index}, {"wrapT", T::Index}};
constexpr Shape kSamplerShape{kSampler};

// camera
constexpr Member kPerspective[] = {
    {"aspectRatio", T::Number}, {"yfov", T::Number}, {"zfar", T::Number}, {"znear", T::Number}};
constexpr Shape kPerspectiveShape{kPerspective};
constexpr Member kOrthographic[] = {
    {"xmag", T::Number}, {"ymag", T::Number}, {"zfar", T::Number}, {"znear", T::Number}};
constexpr Shape kOrthographicShape{kOrthographic};
constexpr Member kCamera[] = {{"name", T::String},
                              {"type", T::String},
                              {"perspective", T::Object, &kPerspectiveShape},
                              {"orthographic", T::Object, &kOrthographicShape}};
constexpr Shape kCameraShape{kCamera};

// Skins are not read (sombra uses the bind pose): their names only, as
// for every object the file names.
constexpr Member kNamed[] = {{"name", T::String}};
constexpr Shape kNamedShape{kNamed};

// animation (spec §22)
constexpr Member kTarget[] = {{"node", T::Index}, {"path", T::String}};
constexpr Shape kTargetShape{kTarget};
constexpr Member kChannel[] = {{"sampler", T::Index}, {"target", T::Object, &kTargetShape}};
constexpr Shape kChannelShape{kChannel};
constexpr Member kAnimationSampler[] = {{"input", T::Index}, {"output", T::Index}, {"interpolation", T::String}};
constexpr Shape kAnimationSamplerShape{kAnimationSampler};
constexpr Member kAnimation[] = {
    {"name", T::String}, {"channels", T::Objects, &kChannelShape}, {"samplers", T::Objects, &kAnimationSamplerShape}};
constexpr Shape kAnimationShape{kAnimation};

// KHR_lights_punctual's lights
constexpr Member kSpot[] = {{"innerConeAngle", T::Number}, {"outerConeAngle", T::Number}};
constexpr Shape kSpotShape{kSpot};
constexpr Member kLight[] = {{"name", T::String},      {"type", T::String},  {"color", T::Numbers, nullptr, 3},
                             {"intensity", T::Number}, {"range", T::Number}, {"spot", T::Object, &kSpotShape}};
constexpr Shape kLightShape{kLight};
constexpr Member kLightsMembers[] = {{"lights", T::Objects, &kLightShape}};
constexpr Shape kLightsShape{kLightsMembers};
constexpr Member kRootExtensions[] = {{kLights, T::Object, &kLightsShape}};
constexpr Shape kRootExtensionsShape{kRootExtensions};

constexpr Member kAsset[] = {
    {"version", T::String}, {"minVersion", T::String}, {"generator", T::String}, {"copyright", T::String}};
constexpr Shape kAssetShape{kAsset};

constexpr Member kRoot[] = {{"asset", T::Object, &kAssetShape},
                            {"extensionsUsed", T::Strings},
                            {"extensionsRequired", T::Strings},
                            {"extensions", T::Object, &kRootExtensionsShape},
                            {"scene", T::Index},
                            {"scenes", T::Objects, &kSceneShape},
                            {"nodes", T::Objects, &kNodeShape},
                            {"meshes", T::Objects, &kMeshShape},
                            {"accessors", T::Objects, &kAccessorShape},
                            {"bufferViews", T::Objects, &kBufferViewShape},
                            {"buffers", T::Objects, &kBufferShape},
                            {"materials", T::Objects, &kMaterialShape},
                            {"textures", T::Objects, &kTextureShape},
                            {"images", T::Objects, &kImageShape},
                            {"samplers", T::Objects, &kSamplerShape},
                            {"cameras", T::Objects, &kCameraShape},
                            {"skins", T::Objects, &kNamedShape},
                            {"animations", T::Objects, &kAnimationShape}};
constexpr Shape kRootShape{kRoot};

// "an array of 3 numbers", for the message.
std::string expected(Type type, int count) {
    const std::string n = count > 0 ? std::to_string(count) + " " : "";
    switch (type) {
        case T::Number: return "a number";
        case T::Index:
        case T::Size: return "a non-negative integer";
        case T::String: return "a string";
        case T::Bool: return "true or false";
        case T::Object: return "an object";
        case T::Objects: return "an array of objects";
        case T::Numbers:
        case T::NumbersOrNull: return "an array of " + n + "numbers";
        case T::Indices: return "an array of non-negative integers";
        case T::Strings: return "an array of strings";
    }
    return "?";
}

// What the file has instead: its kind, or the number itself (a number is
// wrong only where an integer is expected, and then its value says why).
std::string got(const nlohmann::json& v) {
    switch (v.type()) {
        case nlohmann::json::value_t::null: return "null";
        case nlohmann::json::value_t::boolean: return v.get<bool>() ? "true" : "false";
        case nlohmann::json::value_t::string: return "a string";
        case nlohmann::json::value_t::array: return "an array";
        case nlohmann::json::value_t::object: return "an object";
        default: return v.is_number() ? v.dump() : "a binary value";
    }
}

class Checker {
public:
    explicit Checker(const std::string& file) : json_{file, unused_} {}

    void object(const nlohmann::json& v, const Shape& shape, const std::string& at) {
        for (const Member& m : shape.members)
            if (const auto it = v.find(m.key); it != v.end())
                value(*it, m.type, m.shape, m.count, json_child(at, m.key));
        if (shape.others)
            for (const auto& [key, member] : v.items()) value(member, *shape.others, nullptr, 0, json_child(at, key));
    }

private:
    Diagnostics unused_;  // json_fail's context; nothing here warns
    SceneJson json_;

    [[noreturn]] void fail(const std::string& at, Type type, int count, const nlohmann::json& v) {
        json_fail(json_, at, "expected " + expected(type, count) + ", got " + got(v));
    }

    // An integer written without a fraction (tinygltf reads 2.0 as no
    // integer at all), >= 0, and for an Index at most INT_MAX.
    void integer(const nlohmann::json& v, Type type, const std::string& at) {
        if (!v.is_number_unsigned()) fail(at, type, 0, v);
        if (type == T::Index && v.get<std::uint64_t>() > std::uint64_t{INT_MAX})
            json_fail(json_, at, v.dump() + " is too large (at most " + std::to_string(INT_MAX) + ")");
    }

    void value(const nlohmann::json& v, Type type, const Shape* shape, int count, const std::string& at) {
        switch (type) {
            case T::Number:
                if (!v.is_number()) fail(at, type, count, v);
                return;
            case T::Index:
            case T::Size: integer(v, type, at); return;
            case T::String:
                if (!v.is_string()) fail(at, type, count, v);
                return;
            case T::Bool:
                if (!v.is_boolean()) fail(at, type, count, v);
                return;
            case T::Object:
                if (!v.is_object()) fail(at, type, count, v);
                object(v, *shape, at);
                return;
            default: break;
        }
        if (!v.is_array()) fail(at, type, count, v);
        const Type element = type == T::Objects   ? T::Object
                             : type == T::Indices ? T::Index
                             : type == T::Strings ? T::String
                                                  : T::Number;
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (type == T::NumbersOrNull && v[i].is_null()) continue;
            value(v[i], element, shape, 0, json_child(at, i));
        }
    }
};

}  // namespace

void check_json_types(const nlohmann::json& document, const std::string& file) {
    Checker check(file);
    check.object(document, kRootShape, "");
}

}  // namespace sombra::gltf
