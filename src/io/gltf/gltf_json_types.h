// The JSON types of a glTF 2.0 document's members, checked before tinygltf
// parses it (spec §24): tinygltf silently drops a member of the wrong type
// (a string for a number, -1 for an index), and the file would render
// without it.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

namespace sombra::gltf {

// Checks every member sombra reads, wherever it is present: the core glTF 2.0
// objects (asset, scenes, nodes, meshes and primitives, accessors with sparse,
// buffer views, buffers, materials and their textureInfo objects, textures,
// images, samplers, cameras, skins and animations as a whole, every name)
// and the data of the extensions sombra reads. Indices, counts, byte sizes
// and enums (componentType, mode, wrapS...) must be non-negative integers
// written without a fraction; indices and enums must also fit an int.
// Missing members, extras, unknown members and unknown extensions are
// not checked (glTF allows them). Throws Error("FILE: /json/pointer",
// "expected WHAT, got WHAT") for the first wrong value in document order.
void check_json_types(const nlohmann::json& document, const std::string& file);

}  // namespace sombra::gltf
