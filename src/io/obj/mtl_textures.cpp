#include "io/obj/mtl_textures.h"

#include <algorithm>

#include "io/images/texture_image.h"

namespace sombra {

namespace fs = std::filesystem;

TextureRef MtlTextureReader::load(const std::string& name, const tinyobj::texture_option_t& options,
                                  TextureEncoding encoding, const fs::path& folder, const fs::path& mtl_path) {
    TextureRef ref;
    if (name.empty()) return ref;
    std::string file = name;
    std::replace(file.begin(), file.end(), '\\', '/');
    const fs::path path = (folder / fs::path(file)).lexically_normal();
    const std::string source = path.string();
    for (std::size_t i = 0; i < table_.size() && !ref.is_set(); ++i)
        if (table_[i].source == source && table_[i].encoding == encoding) ref.texture = static_cast<std::uint32_t>(i);
    if (!ref.is_set()) {
        if (failed_.count(source) > 0) return ref;
        try {
            ref.texture = add_texture(table_, read_texture_file(path, encoding));
        } catch (const Error& e) {
            failed_.insert(source);
            diag_.warn(mtl_path.string(), "texture '" + name + "': " + e.message() + " (" + e.where() +
                                              "); the material's constant is used");
            return ref;
        }
    }
    if (options.clamp) ref.wrap_u = ref.wrap_v = TextureWrap::Clamp;
    return ref;
}

void MtlTextureReader::apply(const tinyobj::material_t& mtl, const fs::path& mtl_path, Material& m) {
    const fs::path folder = mtl_path.parent_path();
    MaterialTextures& t = m.textures;
    const auto colour = [&](const std::string& name, const tinyobj::texture_option_t& options, Vec3& value,
                            TextureRef& ref) {
        ref = load(name, options, TextureEncoding::Color, folder, mtl_path);
        if (ref.is_set()) value = Vec3{1.0f};
    };
    if (m.type == MaterialType::Pbr)
        colour(mtl.diffuse_texname, mtl.diffuse_texopt, m.base_color, t.base_color);
    else
        colour(mtl.diffuse_texname, mtl.diffuse_texopt, m.kd, t.kd);
    if (m.type == MaterialType::Mirror)
        colour(mtl.specular_texname, mtl.specular_texopt, m.kr, t.kr);
    else if (m.type == MaterialType::Phong)
        colour(mtl.specular_texname, mtl.specular_texopt, m.ks, t.ks);
    colour(mtl.emissive_texname, mtl.emissive_texopt, m.ke, t.ke);

    if (m.type == MaterialType::Pbr) {  // map_Pr, map_Pm: grey data replacing Pr, Pm
        const auto scalar = [&](const std::string& name, const tinyobj::texture_option_t& options, float& value,
                                TextureRef& ref) {
            ref = load(name, options, TextureEncoding::Data, folder, mtl_path);
            if (ref.is_set()) value = 1.0f;
        };
        scalar(mtl.roughness_texname, mtl.roughness_texopt, m.roughness, t.roughness);
        scalar(mtl.metallic_texname, mtl.metallic_texopt, m.metallic, t.metallic);
    }
    t.alpha = load(mtl.alpha_texname, mtl.alpha_texopt, TextureEncoding::Data, folder, mtl_path);
    if (t.alpha.is_set()) {
        const int channels = table_[t.alpha.texture].channels;
        t.alpha.channel = static_cast<std::uint8_t>(channels == 2 || channels == 4 ? 3 : 0);
        t.alpha_test = true;
    }
    t.normal_map = load(mtl.normal_texname, mtl.normal_texopt, TextureEncoding::Data, folder, mtl_path);
    t.bump_map = load(mtl.bump_texname, mtl.bump_texopt, TextureEncoding::Data, folder, mtl_path);
    const float bm = static_cast<float>(mtl.bump_texopt.bump_multiplier);
    t.bump_scale = std::isfinite(bm) ? bm : 1.0f;
    m.textured = any_texture(t);
}

}  // namespace sombra
