// KHR_draco_mesh_compression: the primitive's geometry is one Draco mesh in
// a buffer view; the extension's "attributes" object maps glTF attribute
// names to Draco attribute ids. The primitive's own accessors carry no
// data then (only count, type, and for the decoder's output its meaning).
#include <draco/compression/decode.h>

#include <array>
#include <cmath>
#include <string>

#include "io/gltf/gltf.h"

namespace sombra::gltf {

namespace {

// The Draco attribute id the extension gives `name`, or nothing.
std::optional<std::uint32_t> draco_id(const tinygltf::Value& attributes, const char* name) {
    if (!attributes.IsObject() || !attributes.Has(name)) return std::nullopt;
    const std::optional<int> id = value_int(attributes.Get(name), 0, std::numeric_limits<int>::max());
    if (!id) return std::nullopt;
    return static_cast<std::uint32_t>(*id);
}

const draco::PointAttribute* find_attribute(const draco::Mesh& mesh, std::uint32_t id, const std::string& file,
                                            const std::string& what, const char* name) {
    const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(id);
    if (!att) throw Error(file, what + ": the Draco mesh has no attribute " + std::to_string(id) + " for " + name);
    return att;
}

// What divides an unsigned integer attribute Draco does not mark as
// normalised into glTF's normalised reading, c / (2ⁿ − 1) (1 for anything
// else): glTF colours are floats or normalised unsigned integers, whatever
// the encoder recorded.
float unsigned_normalisation(const draco::PointAttribute& att) {
    if (att.normalized()) return 1.0f;
    switch (att.data_type()) {
        case draco::DT_UINT8: return 255.0f;
        case draco::DT_UINT16: return 65535.0f;
        default: return 1.0f;
    }
}

// One float vector per Draco point from attribute `id` (`components` each),
// with unsigned integers normalised when `normalise_unsigned` (above); empty
// when the attribute is missing. Throws when it is unusable.
std::vector<float> read_attribute(const draco::Mesh& mesh, std::optional<std::uint32_t> id, int components,
                                  const std::string& file, const std::string& what, const char* name,
                                  bool normalise_unsigned = false) {
    if (!id) return {};
    const draco::PointAttribute* att = find_attribute(mesh, *id, file, what, name);
    const float divisor = normalise_unsigned ? unsigned_normalisation(*att) : 1.0f;
    if (att->num_components() < components)
        throw Error(file, what + ": Draco attribute " + std::to_string(*id) + " (" + name + ") has " +
                              std::to_string(att->num_components()) + " components, " + std::to_string(components) +
                              " needed");
    const std::size_t points = mesh.num_points();
    if (!att->is_mapping_identity() && att->indices_map_size() < points)
        throw Error(file, what + ": Draco attribute " + std::to_string(*id) + " maps fewer points than the mesh has");
    std::vector<float> out(points * static_cast<std::size_t>(components));
    for (std::size_t p = 0; p < points; ++p) {
        const draco::AttributeValueIndex value = att->mapped_index(draco::PointIndex(static_cast<std::uint32_t>(p)));
        float* dst = out.data() + p * static_cast<std::size_t>(components);
        if (value.value() >= att->size() || !att->ConvertValue<float>(value, static_cast<std::int8_t>(components), dst))
            throw Error(file, what + ": Draco attribute " + std::to_string(*id) + " (" + name + ") cannot be read");
        for (int c = 0; c < components; ++c) {
            dst[c] /= divisor;
            if (!std::isfinite(dst[c]))
                throw Error(file, what + ": Draco attribute " + std::to_string(*id) + " (" + name + ") is not finite");
        }
    }
    return out;
}

// COLOR_0 from attribute `id` as RGBA per point (alpha 1 for RGB); empty when missing.
std::vector<float> read_colors(const draco::Mesh& mesh, std::optional<std::uint32_t> id, const std::string& file,
                               const std::string& what) {
    if (!id) return {};
    const bool rgba = find_attribute(mesh, *id, file, what, "COLOR_0")->num_components() >= 4;
    std::vector<float> read = read_attribute(mesh, id, rgba ? 4 : 3, file, what, "COLOR_0", true);
    if (rgba) return read;
    std::vector<float> out(read.size() / 3 * 4, 1.0f);
    for (std::size_t i = 0; i < read.size() / 3; ++i)
        for (std::size_t c = 0; c < 3; ++c) out[4 * i + c] = read[3 * i + c];
    return out;
}

}  // namespace

PrimitiveData decode_draco(const AccessorReader& r, const tinygltf::Primitive& primitive,
                           const tinygltf::Value& extension, const std::string& what) {
    if (!extension.IsObject()) throw Error(r.file, what + ": " + kDraco + " is not an object");
    const std::optional<int> view_index =
        extension.Has("bufferView") ? value_int(extension.Get("bufferView"), 0, std::numeric_limits<int>::max())
                                    : std::nullopt;
    if (!view_index) throw Error(r.file, what + ": " + kDraco + " names no bufferView");
    const std::span<const unsigned char> bytes =
        buffer_view_bytes(r.model, *view_index, r.file, what + " (" + kDraco + ")");

    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok())
        throw Error(r.file, what + ": Draco cannot decode the mesh: " + decoded.status().error_msg_string());
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) throw Error(r.file, what + ": Draco cannot decode the mesh");

    const tinygltf::Value& attributes = extension.Has("attributes") ? extension.Get("attributes") : tinygltf::Value();
    if (!draco_id(attributes, "POSITION")) throw Error(r.file, what + ": " + kDraco + " maps no POSITION attribute");
    const std::vector<float> positions =
        read_attribute(*mesh, draco_id(attributes, "POSITION"), 3, r.file, what, "POSITION");
    const std::vector<float> normals =
        primitive.attributes.count("NORMAL")
            ? read_attribute(*mesh, draco_id(attributes, "NORMAL"), 3, r.file, what, "NORMAL")
            : std::vector<float>{};
    std::array<std::vector<float>, kUvSets> uvs;
    for (unsigned set = 0; set < kUvSets; ++set) {
        const std::string name = texcoord_name(set);
        if (primitive.attributes.count(name))
            uvs[set] = read_attribute(*mesh, draco_id(attributes, name.c_str()), 2, r.file, what, name.c_str());
    }
    const std::vector<float> tangents =
        primitive.attributes.count("TANGENT")
            ? read_attribute(*mesh, draco_id(attributes, "TANGENT"), 4, r.file, what, "TANGENT")
            : std::vector<float>{};
    const std::vector<float> colors = primitive.attributes.count("COLOR_0")
                                          ? read_colors(*mesh, draco_id(attributes, "COLOR_0"), r.file, what)
                                          : std::vector<float>{};

    PrimitiveData out;
    out.material = primitive.material;
    const std::size_t points = mesh->num_points();
    out.positions.resize(points);
    for (std::size_t i = 0; i < points; ++i)
        out.positions[i] = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
    if (!normals.empty()) {
        out.normals.resize(points);
        for (std::size_t i = 0; i < points; ++i)
            out.normals[i] = {normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
    }
    for (unsigned set = 0; set < kUvSets; ++set) {
        if (uvs[set].empty()) continue;
        std::vector<Vec2>& to = set == 0 ? out.uvs : out.extra_uvs[set - 1];
        to.resize(points);
        // glTF's v = 0 is the image's top row, sombra's (and OBJ's) the bottom.
        for (std::size_t i = 0; i < points; ++i) to[i] = {uvs[set][2 * i], 1.0f - uvs[set][2 * i + 1]};
    }
    out.tangents = tangents_of(tangents);
    out.colors = colors_of(colors, out.clamped_colors);
    out.indices.reserve(std::size_t{mesh->num_faces()} * 3);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
        for (const draco::PointIndex& p : mesh->face(f)) {
            if (p.value() >= points) throw Error(r.file, what + ": a Draco face refers to a point that does not exist");
            out.indices.push_back(p.value());
        }
    }
    return out;
}

}  // namespace sombra::gltf
