// EXT_meshopt_compression: compressed buffer views decoded with
// meshoptimizer. Every size the file gives is checked against the
// extension's rules and the bytes really present before a decoded buffer
// is allocated; the decoders themselves check that the compressed stream
// holds what the count asks for.
#include "io/gltf/gltf_meshopt.h"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>

namespace sombra::gltf {

namespace {

// The codec's best ratio: an attribute block stores 2 header bits per byte
// of 16 elements (all deltas zero), so a compressed byte decodes to at most
// 64; index streams need a byte per triangle (TRIANGLES) or index (INDICES).
constexpr std::uint64_t kMaxRatio = 64;
// All decoded views together: a small file cannot ask for more.
constexpr std::uint64_t kMaxDecodedBytes = std::uint64_t{2} << 30;

// What a placeholder buffer becomes for tinygltf: one byte of data (tinygltf
// refuses an empty data URI), emptied again after the parse.
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA==";

std::string view_name(std::size_t view) { return "bufferView " + std::to_string(view) + ": " + kMeshopt; }

std::uint64_t size_member(const nlohmann::json& ext, const char* key, bool required, const std::string& where,
                          const std::string& what) {
    const auto it = ext.find(key);
    if (it == ext.end()) {
        if (required) throw Error(where, what + ": " + key + " is missing");
        return 0;
    }
    if (!it->is_number_unsigned()) throw Error(where, what + ": " + key + " must be a non-negative integer");
    return it->get<std::uint64_t>();
}

MeshoptMode mode_of(const nlohmann::json& ext, const std::string& where, const std::string& what) {
    const auto it = ext.find("mode");
    if (it == ext.end()) throw Error(where, what + ": mode is missing");
    const std::string name = it->is_string() ? it->get<std::string>() : it->dump();
    if (name == "ATTRIBUTES") return MeshoptMode::Attributes;
    if (name == "TRIANGLES") return MeshoptMode::Triangles;
    if (name == "INDICES") return MeshoptMode::Indices;
    throw Error(where, what + ": mode '" + name + "' is not ATTRIBUTES, TRIANGLES or INDICES");
}

MeshoptFilter filter_of(const nlohmann::json& ext, const std::string& where, const std::string& what) {
    const auto it = ext.find("filter");
    if (it == ext.end()) return MeshoptFilter::None;
    const std::string name = it->is_string() ? it->get<std::string>() : it->dump();
    if (name == "NONE") return MeshoptFilter::None;
    if (name == "OCTAHEDRAL") return MeshoptFilter::Octahedral;
    if (name == "QUATERNION") return MeshoptFilter::Quaternion;
    if (name == "EXPONENTIAL") return MeshoptFilter::Exponential;
    throw Error(where, what + ": filter '" + name + "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
}

const nlohmann::json* extension_of(const nlohmann::json& object) {
    const auto extensions = object.find("extensions");
    if (extensions == object.end() || !extensions->is_object()) return nullptr;
    const auto ext = extensions->find(kMeshopt);
    return ext != extensions->end() && ext->is_object() ? &*ext : nullptr;
}

bool lists(const nlohmann::json& json, const char* key, const char* name) {
    const auto it = json.find(key);
    return it != json.end() && it->is_array() && std::find(it->begin(), it->end(), name) != it->end();
}

// The extension's rules on the layout (its README, "JSON schema updates").
std::string layout_problem(const MeshoptView& m, std::uint64_t view_stride) {
    const std::uint64_t s = m.byte_stride;
    if (m.count == 0 || s == 0) return "count and byteStride must be at least 1";
    if (view_stride != 0 && view_stride != s)
        return "byteStride " + std::to_string(s) + " differs from the bufferView's " + std::to_string(view_stride);
    switch (m.mode) {
        case MeshoptMode::Attributes:
            if (s % 4 != 0 || s > 256) return "ATTRIBUTES needs a byteStride divisible by 4 and at most 256";
            break;
        case MeshoptMode::Triangles:
            if (m.count % 3 != 0) return "TRIANGLES needs a count divisible by 3";
            [[fallthrough]];
        case MeshoptMode::Indices:
            if (s != 2 && s != 4) return "TRIANGLES and INDICES need a byteStride of 2 or 4";
            if (m.filter != MeshoptFilter::None) return "TRIANGLES and INDICES take no filter";
            break;
    }
    switch (m.filter) {
        case MeshoptFilter::None: break;
        case MeshoptFilter::Octahedral:
            if (s != 4 && s != 8) return "OCTAHEDRAL needs a byteStride of 4 or 8";
            break;
        case MeshoptFilter::Quaternion:
            if (s != 8) return "QUATERNION needs a byteStride of 8";
            break;
        case MeshoptFilter::Exponential:
            if (s % 4 != 0) return "EXPONENTIAL needs a byteStride divisible by 4";
            break;
    }
    return {};
}

// The decoded bytes of one view; its layout and sizes already checked.
std::vector<unsigned char> decode(const MeshoptView& m, std::span<const unsigned char> source, const std::string& where,
                                  const std::string& what) {
    const auto count = static_cast<std::size_t>(m.count);
    const auto stride = static_cast<std::size_t>(m.byte_stride);
    std::vector<unsigned char> out(count * stride);
    int status = 0;
    switch (m.mode) {
        case MeshoptMode::Attributes:
            status = meshopt_decodeVertexBuffer(out.data(), count, stride, source.data(), source.size());
            break;
        case MeshoptMode::Triangles:
            status = meshopt_decodeIndexBuffer(out.data(), count, stride, source.data(), source.size());
            break;
        case MeshoptMode::Indices:
            status = meshopt_decodeIndexSequence(out.data(), count, stride, source.data(), source.size());
            break;
    }
    if (status != 0) {
        static constexpr const char* kModes[] = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
        throw Error(where, what + ": the " + kModes[static_cast<int>(m.mode)] + " data of " +
                               std::to_string(source.size()) + " bytes does not decode to " + std::to_string(count) +
                               " elements of " + std::to_string(stride) + " bytes (meshoptimizer error " +
                               std::to_string(status) + ")");
    }
    switch (m.filter) {
        case MeshoptFilter::None: break;
        case MeshoptFilter::Octahedral: meshopt_decodeFilterOct(out.data(), count, stride); break;
        case MeshoptFilter::Quaternion: meshopt_decodeFilterQuat(out.data(), count, stride); break;
        case MeshoptFilter::Exponential: meshopt_decodeFilterExp(out.data(), count, stride); break;
    }
    return out;
}

}  // namespace

MeshoptPlan prepare_meshopt(nlohmann::json& json, bool glb, const std::string& where) {
    MeshoptPlan plan;
    if (!lists(json, "extensionsUsed", kMeshopt) && !lists(json, "extensionsRequired", kMeshopt)) return plan;
    if (const auto views = json.find("bufferViews"); views != json.end() && views->is_array())
        for (std::size_t i = 0; i < views->size(); ++i) {
            const nlohmann::json* ext = (*views)[i].is_object() ? extension_of((*views)[i]) : nullptr;
            if (!ext) continue;
            const std::string what = view_name(i);
            MeshoptView m;
            m.view = i;
            m.buffer = size_member(*ext, "buffer", true, where, what);
            m.byte_offset = size_member(*ext, "byteOffset", false, where, what);
            m.byte_length = size_member(*ext, "byteLength", true, where, what);
            m.byte_stride = size_member(*ext, "byteStride", true, where, what);
            m.count = size_member(*ext, "count", true, where, what);
            m.mode = mode_of(*ext, where, what);
            m.filter = filter_of(*ext, where, what);
            plan.views.push_back(m);
        }
    if (const auto buffers = json.find("buffers"); buffers != json.end() && buffers->is_array())
        for (std::size_t i = 0; i < buffers->size(); ++i) {
            nlohmann::json& b = (*buffers)[i];
            if (!b.is_object()) continue;
            const nlohmann::json* ext = extension_of(b);
            const bool marked = ext && ext->contains("fallback") && (*ext)["fallback"] == true;
            const bool bin_chunk = glb && i == 0 && !b.contains("uri");
            if (!marked && (bin_chunk || b.contains("uri"))) continue;
            b["uri"] = kPlaceholderUri;
            b["byteLength"] = 1;
            plan.fallback_buffers.push_back(i);
            plan.rewritten = true;
        }
    return plan;
}

void decode_meshopt(tinygltf::Model& model, const MeshoptPlan& plan, const std::string& where) {
    const auto is_fallback = [&plan](std::uint64_t buffer) {
        return std::binary_search(plan.fallback_buffers.begin(), plan.fallback_buffers.end(), buffer);
    };
    for (const std::size_t b : plan.fallback_buffers)
        if (b < model.buffers.size()) {
            model.buffers[b].data.clear();
            model.buffers[b].data.shrink_to_fit();
        }
    std::uint64_t decoded = 0;
    for (const MeshoptView& m : plan.views) {
        const std::string what = view_name(m.view);
        if (m.view >= model.bufferViews.size()) throw Error(where, what + ": the bufferView does not exist");
        tinygltf::BufferView& view = model.bufferViews[m.view];
        if (const std::string problem = layout_problem(m, view.byteStride); !problem.empty())
            throw Error(where, what + ": " + problem);
        // count × byteStride = byteLength, without overflow.
        if (m.count > view.byteLength / m.byte_stride || m.count * m.byte_stride != view.byteLength)
            throw Error(where, what + ": count " + std::to_string(m.count) + " × byteStride " +
                                   std::to_string(m.byte_stride) + " is not the bufferView's byteLength " +
                                   std::to_string(view.byteLength));
        if (m.buffer >= model.buffers.size())
            throw Error(where, what + ": buffer " + std::to_string(m.buffer) + " does not exist");
        if (is_fallback(m.buffer))
            throw Error(where, what + ": buffer " + std::to_string(m.buffer) +
                                   " is a fallback buffer, which holds no compressed data");
        const std::vector<unsigned char>& source = model.buffers[static_cast<std::size_t>(m.buffer)].data;
        if (m.byte_offset > source.size() || m.byte_length > source.size() - m.byte_offset)
            throw Error(where, what + ": " + std::to_string(m.byte_length) + " bytes at byteOffset " +
                                   std::to_string(m.byte_offset) + " overrun buffer " + std::to_string(m.buffer) +
                                   " (" + std::to_string(source.size()) + " bytes)");
        if (view.byteLength / kMaxRatio > m.byte_length)
            throw Error(where, what + ": " + std::to_string(m.byte_length) + " compressed bytes cannot hold " +
                                   std::to_string(view.byteLength) + " (at most " + std::to_string(kMaxRatio) +
                                   " times as many)");
        decoded += view.byteLength;
        if (decoded > kMaxDecodedBytes)
            throw Error(where, what + ": the compressed views decode to more than " +
                                   std::to_string(kMaxDecodedBytes >> 20) + " MiB in all");
        const auto bytes =
            std::span(source).subspan(static_cast<std::size_t>(m.byte_offset), static_cast<std::size_t>(m.byte_length));
        tinygltf::Buffer out;
        out.data = decode(m, bytes, where, what);
        model.buffers.push_back(std::move(out));
        view.buffer = static_cast<int>(model.buffers.size() - 1);
        view.byteOffset = 0;
    }
    for (std::size_t i = 0; i < model.bufferViews.size(); ++i)
        if (const int b = model.bufferViews[i].buffer; b >= 0 && is_fallback(static_cast<std::uint64_t>(b)))
            throw Error(where, "bufferView " + std::to_string(i) + " refers to buffer " + std::to_string(b) +
                                   ", a fallback buffer without data, but has no " + kMeshopt + " of its own");
}

}  // namespace sombra::gltf
