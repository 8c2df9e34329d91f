// Textures in scene-file materials (spec §12): any colour parameter may be
// {"texture": file, "scale": [r, g, b]}, a scalar one {"texture": file,
// "channel": "g", "scale": s}; "normal_map": file and "alpha": {"texture":
// file, "cutoff": c} go on any material. Files are relative to the scene's
// folder; a missing one is an error; each is decoded once per encoding.
#include <cstring>
#include <string>

#include "io/images/texture_image.h"
#include "io/scene_json/scene_json.h"

namespace sombra {

namespace fs = std::filesystem;

namespace {

constexpr const char* kChannels = "rgba";

// The texture `file` names, decoded into the table (or found there).
TextureRef load_texture(const SceneJson& s, const Json& file_value, std::string_view pointer, TextureEncoding encoding,
                        SceneTextures& textures) {
    const std::string& file = read_string(s, file_value, pointer);
    if (file.empty()) json_fail(s, pointer, "expected an image file name, not an empty string");
    if (file.find('\0') != std::string::npos) json_fail(s, pointer, "the file name contains a NUL character");
    const fs::path path = (textures.folder / fs::path(file)).lexically_normal();
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) json_fail(s, pointer, "cannot open texture '" + file + "': no such file");
    if (!fs::is_regular_file(status)) json_fail(s, pointer, "texture '" + file + "' is not a regular file");

    TextureRef ref;
    for (std::size_t i = 0; i < textures.table->size(); ++i) {
        const Texture& t = (*textures.table)[i];
        if (t.source == path.string() && t.encoding == encoding) ref.texture = static_cast<std::uint32_t>(i);
    }
    if (!ref.is_set())
        ref.texture = add_texture(*textures.table, read_texture_file(path, encoding));  // its errors name the image
    return ref;
}

Vec3 read_rgb_in(const SceneJson& s, const Json& v, std::string_view pointer, std::string_view key, bool reflectance) {
    const Vec3 c = read_vec3(s, v, pointer);
    if (reflectance && (min_component(c) < 0 || max_component(c) > 1))
        json_fail(s, pointer, std::string(key) + " components must lie in [0, 1]");
    if (min_component(c) < 0) json_fail(s, pointer, "colour components must be non-negative");
    return c;
}

float read_unit_float(const SceneJson& s, const Json& v, std::string_view pointer, std::string_view key) {
    const float x = read_float(s, v, pointer);
    if (x < 0 || x > 1) json_fail(s, pointer, std::string(key) + " must lie in [0, 1]");
    return x;
}

void read_rgb_slot(const SceneJson& s, const Json& v, std::string_view pointer, const RgbTextureSlot& slot, Material& m,
                   SceneTextures& textures) {
    if (!v.is_object()) {
        if (!v.is_array())
            json_fail(s, pointer,
                      "expected an array of 3 numbers or a texture {\"texture\": file, \"scale\": [r, g, b]}");
        m.*slot.value = read_rgb_in(s, v, pointer, slot.key, slot.reflectance);
        return;
    }
    expect_keys(s, v, pointer, {"texture", "scale"});
    const Json& file = require_member(s, v, pointer, "texture");
    m.*slot.value = Vec3{1.0f};
    if (const Json* scale = find_member(v, "scale"))
        m.*slot.value = read_rgb_in(s, *scale, json_child(pointer, "scale"), slot.key, slot.reflectance);
    m.textures.*slot.texture = load_texture(s, file, json_child(pointer, "texture"), TextureEncoding::Color, textures);
}

void read_scalar_slot(const SceneJson& s, const Json& v, std::string_view pointer, const ScalarTextureSlot& slot,
                      Material& m, SceneTextures& textures) {
    if (!v.is_object()) {
        if (!v.is_number())
            json_fail(s, pointer, "expected a number or a texture {\"texture\": file, \"channel\": \"g\"}");
        m.*slot.value = read_unit_float(s, v, pointer, slot.key);
        return;
    }
    expect_keys(s, v, pointer, {"texture", "channel", "scale"});
    const Json& file = require_member(s, v, pointer, "texture");
    TextureRef ref = load_texture(s, file, json_child(pointer, "texture"), TextureEncoding::Data, textures);
    if (const Json* channel = find_member(v, "channel")) {
        const std::string p = json_child(pointer, "channel");
        const std::string& name = read_string(s, *channel, p);
        const char* at = name.size() == 1 ? std::strchr(kChannels, name[0]) : nullptr;
        if (!at || *at == '\0')
            json_fail(s, p, "unknown channel '" + name + "' (expected \"r\", \"g\", \"b\" or \"a\")");
        ref.channel = static_cast<std::uint8_t>(at - kChannels);
    }
    m.*slot.value = 1.0f;
    if (const Json* scale = find_member(v, "scale"))
        m.*slot.value = read_unit_float(s, *scale, json_child(pointer, "scale"), slot.key);
    m.textures.*slot.texture = ref;
}

}  // namespace

void read_texturable(const SceneJson& s, const Json& material, std::string_view pointer, std::string_view key,
                     bool required, Material& m, SceneTextures& textures) {
    const Json* v = find_member(material, key);
    if (!v) {
        if (required) require_member(s, material, pointer, key);  // fails, naming the key
        return;
    }
    const std::string p = json_child(pointer, key);
    for (const RgbTextureSlot& slot : kRgbTextureSlots)
        if (key == slot.key) return read_rgb_slot(s, *v, p, slot, m, textures);
    for (const ScalarTextureSlot& slot : kScalarTextureSlots)
        if (key == slot.key) return read_scalar_slot(s, *v, p, slot, m, textures);
    // A key missing from the slot tables (append: GCC 12's false -Wrestrict on literal + std::string).
    json_fail(s, p, std::string("'").append(key).append("' cannot be textured"));
}

void read_material_maps(const SceneJson& s, const Json& material, std::string_view pointer, Material& m,
                        SceneTextures& textures) {
    if (const Json* normal = find_member(material, "normal_map")) {
        m.textures.normal_map =
            load_texture(s, *normal, json_child(pointer, "normal_map"), TextureEncoding::Data, textures);
    }
    if (const Json* alpha = find_member(material, "alpha")) {
        const std::string p = json_child(pointer, "alpha");
        expect_object(s, *alpha, p);
        expect_keys(s, *alpha, p, {"texture", "cutoff"});
        TextureRef ref = load_texture(s, require_member(s, *alpha, p, "texture"), json_child(p, "texture"),
                                      TextureEncoding::Data, textures);
        const Texture& t = (*textures.table)[ref.texture];
        ref.channel = static_cast<std::uint8_t>(t.channels == 2 || t.channels == 4 ? 3 : 0);
        m.textures.alpha = ref;
        m.textures.alpha_test = true;
        if (const Json* cutoff = find_member(*alpha, "cutoff"))
            m.textures.alpha_cutoff = read_unit_float(s, *cutoff, json_child(p, "cutoff"), "cutoff");
    }
    m.textured = any_texture(m.textures);
}

}  // namespace sombra
