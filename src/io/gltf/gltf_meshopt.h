// EXT_meshopt_compression (spec §24), private to src/io/gltf: buffer views
// whose bytes are stored compressed in another buffer, decoded with
// meshoptimizer (Debian's libmeshoptimizer-dev) before any accessor reads
// them. Two steps around tinygltf's parse (gltf_file.cpp): the extension's
// objects are read from the JSON, and the fallback buffers it allows (no
// data, or data sombra need not read) are replaced by placeholders that
// tinygltf accepts; after the parse every compressed view is decoded into a
// buffer of its own.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "io/gltf/gltf.h"

namespace sombra::gltf {

enum class MeshoptMode { Attributes, Triangles, Indices };
enum class MeshoptFilter { None, Octahedral, Quaternion, Exponential };

// One buffer view's extension object, as the file gives it.
struct MeshoptView {
    std::size_t view = 0;  // the bufferView it belongs to
    std::uint64_t buffer = 0, byte_offset = 0, byte_length = 0, byte_stride = 0, count = 0;
    MeshoptMode mode = MeshoptMode::Attributes;
    MeshoptFilter filter = MeshoptFilter::None;
};

struct MeshoptPlan {
    std::vector<MeshoptView> views;
    std::vector<std::size_t> fallback_buffers;  // buffers whose data is not read (sorted)
    bool rewritten = false;                     // the JSON changed: tinygltf must parse the new text
};

// When the file lists EXT_meshopt_compression in extensionsUsed: reads every
// bufferView's extension object (checked: required members present, mode and
// filter names known) and replaces, in `json`, each fallback buffer (one
// marked "fallback": true, or one without a uri other than a GLB's buffer 0)
// by a one-byte placeholder. Without the extension it changes nothing and
// returns an empty plan. Throws Error(where, "bufferView N: EXT_meshopt_compression: ...").
MeshoptPlan prepare_meshopt(nlohmann::json& json, bool glb, const std::string& where);

// Decodes every view of `plan` into a new buffer of `model` (the view then
// points at it, at offset 0), after checking the extension's rules (count ×
// byteStride = the view's byteLength, the strides each mode and filter
// allow, the compressed bytes inside their buffer, at most 64 decoded bytes
// per compressed byte, at most 2 GiB decoded in all) before anything is
// allocated; then empties the fallback buffers and checks that no other
// view refers to them. Throws Error(where, "bufferView N: ...").
void decode_meshopt(tinygltf::Model& model, const MeshoptPlan& plan, const std::string& where);

}  // namespace sombra::gltf
