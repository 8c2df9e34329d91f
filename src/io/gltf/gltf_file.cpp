// glTF file → tinygltf::Model, with the guards that tinygltf lacks on
// hostile input. This is the one translation unit that compiles tinygltf's
// implementation (header-only, Debian's libtinygltf-dev; JSON through
// nlohmann-json), configured in io/gltf/gltf.h.
#define TINYGLTF_IMPLEMENTATION
#include "io/gltf/gltf.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <set>

#include "io/gltf/gltf_json_types.h"
#include "io/gltf/gltf_meshopt.h"
#include "io/mesh_builder.h"

namespace sombra::gltf {

namespace fs = std::filesystem;

namespace {

// tinygltf takes a 32-bit size; real models stay far below.
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{1} << 30;
// All external buffer files together. A file can name the same .bin in many
// buffers; each is read whole, so this bounds what such a file costs.
constexpr std::uint64_t kMaxExternalBytes = std::uint64_t{2} << 30;

constexpr std::uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

std::uint32_t read_u32(const std::string& bytes, std::size_t at) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
    return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24;
}

// What the filesystem callbacks know: the model's folder and how much they read.
struct FileAccess {
    fs::path folder;
    std::uint64_t bytes_read = 0;
};

// Only files inside the model's folder (tinygltf also tries the working
// directory, where a missing buffer would be found by accident).
bool file_exists(const std::string& path, void* user) {
    const auto* access = static_cast<const FileAccess*>(user);
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(path, ec);
    if (ec) return false;
    const fs::path folder = fs::weakly_canonical(access->folder, ec);
    if (ec) return false;
    const auto mismatch = std::mismatch(folder.begin(), folder.end(), canonical.begin(), canonical.end());
    return mismatch.first == folder.end() && fs::is_regular_file(canonical, ec);
}

std::string expand_path(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* access = static_cast<FileAccess*>(user);
    try {
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(path, ec);
        if (ec || access->bytes_read + size > kMaxExternalBytes) {
            if (err) *err = "external buffers exceed " + std::to_string(kMaxExternalBytes >> 20) + " MiB in all";
            return false;
        }
        const std::string bytes = read_mesh_file(path);  // regular files only, errors named
        access->bytes_read += bytes.size();
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const Error& e) {
        if (err) *err = e.message();
        return false;
    }
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "writing is not supported";
    return false;
}

// Images are not decoded here (gltf_textures.cpp decodes those a material
// uses). A data: URI's bytes reach only this callback, so they are kept,
// encoded, in image->image; a buffer view's are not (tinygltf hands them
// over without checking the view against its buffer: gltf_textures.cpp
// reads views itself, checked). External files are not read (NO_EXTERNAL_IMAGE).
bool keep_data_uri_image(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes,
                         int size, void*) {
    if (image->bufferView < 0 && bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

// The first line of tinygltf's message, trimmed.
std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r' || line.back() == '.')) line.pop_back();
    return line.empty() ? "invalid glTF" : line;
}

// The GLB container (glTF 2.0 §4.4): header, a JSON chunk, an optional BIN
// chunk, each 4-byte aligned and inside the file. Returns the JSON chunk.
std::string_view check_glb(const std::string& bytes, const std::string& where) {
    if (bytes.size() < 20) throw Error(where, "not a GLB file: shorter than its 20-byte header");
    if (read_u32(bytes, 0) != kGlbMagic) throw Error(where, "not a GLB file: the file does not start with 'glTF'");
    if (const std::uint32_t version = read_u32(bytes, 4); version != 2)
        throw Error(where, "GLB container version " + std::to_string(version) + " (only 2 is supported)");
    const std::uint64_t length = read_u32(bytes, 8);
    if (length != bytes.size())
        throw Error(where, "the GLB header gives a length of " + std::to_string(length) + " bytes, the file has " +
                               std::to_string(bytes.size()));
    const std::uint64_t json_length = read_u32(bytes, 12);
    if (read_u32(bytes, 16) != kChunkJson) throw Error(where, "the first GLB chunk is not JSON");
    if (json_length == 0 || 20 + json_length > length)
        throw Error(where, "the GLB JSON chunk's length (" + std::to_string(json_length) + ") overruns the file");
    const std::uint64_t bin_start = 20 + json_length;
    if (bin_start < length) {
        if (bin_start % 4 != 0) throw Error(where, "the GLB JSON chunk's end is not 4-byte aligned");
        if (bin_start + 8 > length) throw Error(where, "a GLB chunk header is cut short");
        const std::uint64_t bin_length = read_u32(bytes, bin_start);
        if (read_u32(bytes, bin_start + 4) != kChunkBin) throw Error(where, "the second GLB chunk is not BIN");
        if (bin_start + 8 + bin_length > length)
            throw Error(where, "the GLB BIN chunk's length (" + std::to_string(bin_length) + ") overruns the file");
    }
    return std::string_view(bytes).substr(20, json_length);
}

nlohmann::json parse_json(std::string_view text, const std::string& where) {
    nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
    if (json.is_discarded()) throw Error(where, "the glTF JSON is not valid JSON");
    if (!json.is_object()) throw Error(where, "the glTF JSON is not a JSON object");
    return json;
}

// tinygltf copies the BIN chunk into every buffer without a uri: only the
// first buffer of a GLB may refer to it (glTF 2.0 §4.4.3.3), and a .gltf's
// buffers all need one. Checked on the JSON before tinygltf sees it, so that
// a thousand such buffers cost nothing, and after EXT_meshopt_compression's
// fallback buffers, which may have none, became placeholders.
void check_buffers(const nlohmann::json& json, bool glb, const std::string& where) {
    const auto buffers = json.find("buffers");
    if (buffers == json.end() || !buffers->is_array()) return;
    for (std::size_t i = glb ? 1 : 0; i < buffers->size(); ++i) {
        const nlohmann::json& b = (*buffers)[i];
        if (b.is_object() && !b.contains("uri"))
            throw Error(where, "buffer " + std::to_string(i) + " has no uri: " +
                                   (glb ? "only buffer 0 may refer to the GLB's BIN chunk"
                                        : "only a fallback buffer of EXT_meshopt_compression may have none"));
    }
}

// A Draco primitive's "indices" accessor has no buffer view (Draco holds
// the faces), which tinygltf 2.7 rejects unless it decodes Draco itself.
// sombra decodes Draco with its own checks (gltf_draco.cpp) and takes the
// faces from the Draco mesh, so the reference is removed before tinygltf
// parses the JSON. Returns whether anything was removed.
bool strip_draco_indices(nlohmann::json& json) {
    bool changed = false;
    const auto meshes = json.find("meshes");
    if (meshes == json.end() || !meshes->is_array()) return false;
    for (nlohmann::json& mesh : *meshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (nlohmann::json& p : mesh["primitives"]) {
            if (!p.is_object() || !p.contains("extensions") || !p["extensions"].is_object()) continue;
            if (p["extensions"].contains(kDraco) && p.erase("indices") > 0) changed = true;
        }
    }
    return changed;
}

// emissiveFactor's null entries (obj2gltf writes them) read as 0, with one
// warning (spec §24); tinygltf would drop the whole array for one null.
// Returns whether anything was replaced.
bool zero_null_emissive(nlohmann::json& json, const std::string& where, Diagnostics& diag) {
    const auto materials = json.find("materials");
    if (materials == json.end() || !materials->is_array()) return false;
    std::size_t replaced = 0, in_materials = 0;
    for (nlohmann::json& m : *materials) {
        if (!m.is_object() || !m.contains("emissiveFactor") || !m["emissiveFactor"].is_array()) continue;
        bool any = false;
        for (nlohmann::json& x : m["emissiveFactor"])
            if (x.is_null()) {
                x = 0;
                ++replaced;
                any = true;
            }
        in_materials += any ? 1 : 0;
    }
    if (replaced > 0)
        diag.warn(where, "emissiveFactor: " + std::to_string(replaced) + " null entries in " +
                             std::to_string(in_materials) + " materials read as 0");
    return replaced > 0;
}

// The GLB container again, with a new JSON chunk (space-padded to 4 bytes)
// and the original BIN chunk, if any.
std::string rebuild_glb(const std::string& bytes, std::string_view json_chunk, std::string json) {
    while (json.size() % 4 != 0) json.push_back(' ');
    const std::size_t bin_start = 20 + json_chunk.size();
    const std::string_view rest =
        bin_start < bytes.size() ? std::string_view(bytes).substr(bin_start) : std::string_view();
    std::string out(20, '\0');
    const auto put = [&out](std::size_t at, std::uint64_t value) {
        for (int i = 0; i < 4; ++i) out[at + std::size_t(i)] = static_cast<char>((value >> (8 * i)) & 0xff);
    };
    put(0, kGlbMagic);
    put(4, 2);
    put(8, 20 + json.size() + rest.size());
    put(12, json.size());
    put(16, kChunkJson);
    out += json;
    out += rest;
    return out;
}

bool supported_extension(const std::string& name) {
    static const std::set<std::string> supported{kDraco,
                                                 kQuantization,
                                                 kLights,
                                                 kIor,
                                                 kEmissiveStrength,
                                                 kTextureTransform,
                                                 kSpecular,
                                                 kTransmission,
                                                 kVolume,
                                                 kClearcoat,
                                                 kSheen,
                                                 kUnlit,
                                                 kMeshopt,
                                                 kWebp,
                                                 kGpuInstancing};
    return supported.count(name) > 0;
}

void check_required_extension(const std::string& name, const std::string& where) {
    if (!supported_extension(name)) throw Error(where, "requires the unsupported glTF extension " + name);
}

// The checks on the JSON before tinygltf reads it: an unsupported extension
// in extensionsRequired first (spec §24: it is named before any check its
// data would fail), then the members' types. Another glTF version follows
// another schema: the version check after parsing names it.
void check_document(const nlohmann::json& json, const std::string& where) {
    if (const auto asset = json.find("asset"); asset != json.end() && asset->is_object())
        if (const auto version = asset->find("version");
            version != asset->end() && version->is_string() && version->get<std::string>().rfind("2.", 0) != 0)
            return;
    if (const auto required = json.find("extensionsRequired"); required != json.end() && required->is_array())
        for (const nlohmann::json& name : *required)
            if (name.is_string()) check_required_extension(name.get<std::string>(), where);
    check_json_types(json, where);
}

void check_extensions(const tinygltf::Model& model, const std::string& where, Diagnostics& diag) {
    for (const std::string& name : model.extensionsRequired) check_required_extension(name, where);
    std::string ignored;
    for (const std::string& name : model.extensionsUsed) {
        if (supported_extension(name) || ignored.find(name) != std::string::npos) continue;
        ignored += (ignored.empty() ? "" : ", ") + name;
    }
    if (!ignored.empty()) diag.warn(where, "ignoring the unsupported glTF extensions " + ignored);
}

}  // namespace

tinygltf::Model parse_file(const fs::path& path, Diagnostics& diag) {
    const std::string where = path.string();
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > kMaxFileBytes)
        throw Error(where, "glTF file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
    std::string bytes = read_mesh_file(path);
    if (bytes.size() > kMaxFileBytes)
        throw Error(where, "glTF file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");

    const bool binary = bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic;
    MeshoptPlan meshopt;
    if (binary) {
        const std::string_view json_chunk = check_glb(bytes, where);
        nlohmann::json json = parse_json(json_chunk, where);
        check_document(json, where);
        meshopt = prepare_meshopt(json, true, where);
        check_buffers(json, true, where);
        const bool draco = json_chunk.find(kDraco) != std::string_view::npos && strip_draco_indices(json);
        const bool nulls = zero_null_emissive(json, where, diag);
        if (draco || meshopt.rewritten || nulls)
            bytes = rebuild_glb(bytes, json_chunk, json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    } else {
        // Text that is no JSON object is left to tinygltf, which names what is wrong.
        nlohmann::json json = nlohmann::json::parse(bytes, nullptr, false);
        if (json.is_object()) {
            check_document(json, where);
            meshopt = prepare_meshopt(json, false, where);
            check_buffers(json, false, where);
            const bool draco = bytes.find(kDraco) != std::string::npos && strip_draco_indices(json);
            const bool nulls = zero_null_emissive(json, where, diag);
            if (draco || meshopt.rewritten || nulls)
                bytes = json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        }
    }
    if (bytes.size() > kMaxFileBytes)
        throw Error(where, "glTF file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");

    FileAccess access{path.parent_path().empty() ? fs::path(".") : path.parent_path()};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&file_exists, &expand_path, &read_whole_file, &write_whole_file, &access});
    loader.SetImageLoader(&keep_data_uri_image, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const std::string folder = access.folder.string();
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                  reinterpret_cast<const unsigned char*>(bytes.data()),
                                                  static_cast<unsigned int>(bytes.size()), folder)
                    : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                                 static_cast<unsigned int>(bytes.size()), folder);
    } catch (const std::exception& e) {  // nlohmann's, on JSON tinygltf did not expect
        throw Error(where, std::string("invalid glTF: ") + e.what());
    }
    if (!ok) throw Error(where, first_line(err.empty() ? warn : err));
    if (model.asset.version.rfind("2.", 0) != 0)
        throw Error(where, "glTF version '" + model.asset.version + "' (only 2.x is supported)");
    check_extensions(model, where, diag);
    decode_meshopt(model, meshopt, where);
    return model;
}

}  // namespace sombra::gltf
