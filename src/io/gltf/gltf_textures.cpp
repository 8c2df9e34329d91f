// glTF materials' textures (spec §12, §13): the images their texture
// references name, decoded by the texture module and wired into the
// materials' texture slots.
#include <cmath>
#include <map>
#include <span>

#include "core/base64.h"
#include "io/gltf/gltf.h"
#include "io/images/texture_image.h"
#include "scene/texture.h"

namespace sombra::gltf {

namespace {

TextureWrap wrap_of(GltfWrap w) {
    switch (w) {
        case GltfWrap::ClampToEdge: return TextureWrap::Clamp;
        case GltfWrap::MirroredRepeat: return TextureWrap::MirroredRepeat;
        case GltfWrap::Repeat: break;
    }
    return TextureWrap::Repeat;
}

// %XX escapes of a URI, decoded (glTF image URIs are URI-encoded: "my%20wood.png").
std::string decode_uri(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        const auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
        if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) && hex(uri[i + 2])) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

class TextureTable {
public:
    TextureTable(const tinygltf::Model& model, const std::filesystem::path& path, std::vector<Texture>& textures,
                 Diagnostics& diag)
        : model_(model), path_(path), file_(path.string()), textures_(textures), diag_(diag) {}

    // The table index of image `image` decoded as `encoding`, or kNoTexture
    // when its file is missing (warned once).
    std::uint32_t index(int image, TextureEncoding encoding) {
        const auto key = std::pair{image, encoding};
        if (const auto it = decoded_.find(key); it != decoded_.end()) return it->second;
        const std::uint32_t i = decode(image, encoding);
        decoded_.emplace(key, i);
        return i;
    }

private:
    std::uint32_t decode(int index, TextureEncoding encoding) {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.images.size())
            throw Error(file_, "a texture names image " + std::to_string(index) + ", but the file has " +
                                   std::to_string(model_.images.size()));
        const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
        const std::string source = file_ + ": /images/" + std::to_string(index);
        if (image.bufferView >= 0)
            return add_texture(textures_, decode_texture(buffer_view_bytes(model_, image.bufferView, file_,
                                                                           "image " + std::to_string(index)),
                                                         encoding, source));
        if (!image.image.empty()) return add_texture(textures_, decode_texture(image.image, encoding, source));
        if (image.uri.empty()) throw Error(file_, "image " + std::to_string(index) + " has neither data nor a uri");
        // A data: URI of a type tinygltf does not decode (image/webp).
        if (image.uri.rfind("data:", 0) == 0) {
            const std::size_t comma = image.uri.find(',');
            const std::optional<std::string> bytes =
                comma != std::string::npos && image.uri.substr(0, comma).ends_with(";base64")
                    ? base64_decode(std::string_view(image.uri).substr(comma + 1))
                    : std::nullopt;
            if (!bytes || bytes->empty())
                throw Error(file_, "image " + std::to_string(index) + ": the data: URI holds no base64 data");
            const auto* data = reinterpret_cast<const unsigned char*>(bytes->data());
            return add_texture(textures_, decode_texture(std::span(data, bytes->size()), encoding, source));
        }

        // A file beside the model, never outside its folder.
        const std::filesystem::path relative = std::filesystem::path(decode_uri(image.uri)).lexically_normal();
        if (relative.is_absolute() || relative.empty() || *relative.begin() == "..")
            throw Error(file_,
                        "image " + std::to_string(index) + ": '" + image.uri + "' lies outside the model's folder");
        const std::filesystem::path file = path_.parent_path() / relative;
        std::error_code ec;
        if (!std::filesystem::exists(file, ec)) {
            diag_.warn(file_, "image " + std::to_string(index) + ": '" + image.uri +
                                  "' not found: the material's constant is used instead");
            return kNoTexture;
        }
        return add_texture(textures_, read_texture_file(file, encoding));
    }

    const tinygltf::Model& model_;
    const std::filesystem::path& path_;
    std::string file_;
    std::vector<Texture>& textures_;
    Diagnostics& diag_;
    std::map<std::pair<int, TextureEncoding>, std::uint32_t> decoded_;
};

}  // namespace

UvTransform uv_transform_of(Vec2 offset, float rotation, Vec2 scale) {
    // glTF (v down): uv' = offset + R · (scale ⊙ uv), R = [[cos, sin], [−sin, cos]]
    // (the extension's column-major GLSL mat3). sombra keeps w = 1 − v, so
    //   u' = cos·sx·u − sin·sy·w + (ox + sin·sy)
    //   w' = sin·sx·u + cos·sy·w + (1 − oy − cos·sy).
    const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
    const double sx = scale.x, sy = scale.y, ox = offset.x, oy = offset.y;
    UvTransform t;
    t.uu = float(c * sx), t.uv = float(-s * sy), t.u0 = float(ox + s * sy);
    t.vu = float(s * sx), t.vv = float(c * sy), t.v0 = float(1.0 - oy - c * sy);
    return t;
}

namespace {

bool finite_transform(const UvTransform& t) {
    return std::isfinite(t.uu) && std::isfinite(t.uv) && std::isfinite(t.u0) && std::isfinite(t.vu) &&
           std::isfinite(t.vv) && std::isfinite(t.v0);
}

// The texture slot for a glTF texture reference: its image decoded as
// `encoding`, its sampler's wrap modes, its KHR_texture_transform, channel `channel`.
struct SlotMaker {
    const tinygltf::Model& model;
    const std::string& file;
    TextureTable& table;

    TextureRef operator()(const GltfTextureRef& ref, TextureEncoding encoding, std::uint8_t channel = 0) const {
        TextureRef slot;
        if (!ref.present() || ref.texcoord < 0 || ref.texcoord >= int(kUvSets)) return slot;
        if (ref.image < 0) return slot;
        if (ref.offset.x != 0 || ref.offset.y != 0 || ref.rotation != 0 || ref.scale.x != 1 || ref.scale.y != 1) {
            slot.transformed = true;
            slot.uv_transform = uv_transform_of(ref.offset, ref.rotation, ref.scale);
            if (!finite_transform(slot.uv_transform))
                throw Error(file, "texture " + std::to_string(ref.texture) + ": " + kTextureTransform +
                                      " overflows (offset, rotation and scale give a non-finite matrix)");
        }
        slot.texture = table.index(ref.image, encoding);
        slot.wrap_u = wrap_of(ref.wrap_s);
        slot.wrap_v = wrap_of(ref.wrap_t);
        slot.channel = channel;
        slot.uv_set = static_cast<std::uint8_t>(ref.texcoord);
        return slot;
    }
};

}  // namespace

void apply_textures(const tinygltf::Model& model, const std::filesystem::path& path,
                    const std::vector<GltfMaterialTextures>& refs, std::vector<Material>& materials,
                    std::vector<Texture>& textures, Diagnostics& diag) {
    const std::string file = path.string();
    TextureTable table(model, path, textures, diag);
    int unapplied_texcoords = 0;  // references, not slots: metallicRoughness fills two
    const SlotMaker slot{model, file, table};
    for (std::size_t i = 0; i < refs.size() && i < materials.size(); ++i) {
        const GltfMaterialTextures& r = refs[i];
        for (const GltfTextureRef* ref : {&r.base_color, &r.metallic_roughness, &r.normal, &r.emissive, &r.specular,
                                          &r.specular_color, &r.transmission, &r.clearcoat, &r.clearcoat_roughness,
                                          &r.clearcoat_normal, &r.sheen_color, &r.sheen_roughness})
            unapplied_texcoords += ref->present() && ref->texcoord >= int(kUvSets) ? 1 : 0;
        MaterialTextures& t = materials[i].textures;
        t.base_color = slot(r.base_color, TextureEncoding::Color);
        t.roughness = slot(r.metallic_roughness, TextureEncoding::Data, 1);
        t.metallic = slot(r.metallic_roughness, TextureEncoding::Data, 2);
        t.normal_map = slot(r.normal, TextureEncoding::Data);
        t.normal_scale = r.normal.strength;
        t.ke = slot(r.emissive, TextureEncoding::Color);
        t.specular = slot(r.specular, TextureEncoding::Data, 3);
        t.specular_color = slot(r.specular_color, TextureEncoding::Color);
        t.transmission = slot(r.transmission, TextureEncoding::Data, 0);
        t.clearcoat = slot(r.clearcoat, TextureEncoding::Data, 0);
        t.clearcoat_roughness = slot(r.clearcoat_roughness, TextureEncoding::Data, 1);
        t.clearcoat_normal_map = slot(r.clearcoat_normal, TextureEncoding::Data);
        t.clearcoat_normal_scale = r.clearcoat_normal.strength;
        t.sheen_color = slot(r.sheen_color, TextureEncoding::Color);
        t.sheen_roughness = slot(r.sheen_roughness, TextureEncoding::Data, 3);
        if (r.alpha_mode != AlphaMode::Opaque) {
            // Alpha is baseColorFactor's A times the base colour image's A
            // (never sRGB-decoded, so the colour image serves as it is).
            t.alpha_test = true;
            t.alpha_factor = r.base_alpha;
            t.alpha_cutoff = r.alpha_mode == AlphaMode::Mask ? r.alpha_cutoff : 0.5f;
            if (t.base_color.is_set()) {
                t.alpha = t.base_color;
                t.alpha.channel = 3;
            }
        }
        materials[i].textured = any_texture(t);
    }
    if (unapplied_texcoords > 0)
        diag.warn(file, std::to_string(unapplied_texcoords) + " texture references use a TEXCOORD beyond " +
                            texcoord_name(kUvSets - 1) + ": not applied (their constants are used)");
}

}  // namespace sombra::gltf
