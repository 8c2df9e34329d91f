// glTF materials → sombra's `pbr` material (spec §11, §13), their texture
// references (as the file gives them; gltf_textures.cpp applies them), and
// KHR_lights_punctual lights (point, spot, directional).
#include <algorithm>
#include <climits>
#include <cmath>
#include <numbers>

#include "io/gltf/gltf.h"

#include "core/format.h"

namespace sombra::gltf {

std::optional<int> value_int(const tinygltf::Value& v, int lo, int hi) {
    if (!v.IsNumber()) return std::nullopt;
    const double d = v.GetNumberAsDouble();  // exact for every int tinygltf stores
    if (!(d >= lo && d <= hi) || d != std::floor(d)) return std::nullopt;
    return static_cast<int>(d);
}

namespace {

// Lumens per watt: the luminous efficacy that turns glTF's photometric
// intensity (candela) into radiant intensity (W/sr), as Blender's importer does.
constexpr float kLumensPerWatt = 683.0f;

struct MaterialContext {
    const tinygltf::Model& model;
    const std::string& file;
    std::string what;  // "material 3"
    Diagnostics& diag;
};

// A colour of 3 (or more: alpha ignored) finite components; `fallback` when absent.
Vec3 read_colour(const MaterialContext& c, const std::vector<double>& v, Vec3 fallback, const char* name) {
    if (v.empty()) return fallback;
    if (v.size() < 3) throw Error(c.file, c.what + ": " + name + " has fewer than 3 components");
    const Vec3 colour{float(v[0]), float(v[1]), float(v[2])};
    if (!is_finite(colour)) throw Error(c.file, c.what + ": " + name + " is not finite");
    return colour;
}

float clamped(const MaterialContext& c, double value, const char* name) {
    const float x = static_cast<float>(value);
    if (!std::isfinite(x)) throw Error(c.file, c.what + ": " + name + " is not finite");
    if (x < 0.0f || x > 1.0f) c.diag.warn(c.file, c.what + ": " + name + " outside [0, 1] clamped");
    return std::clamp(x, 0.0f, 1.0f);
}

GltfWrap wrap_mode(int gl) {
    switch (gl) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return GltfWrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return GltfWrap::MirroredRepeat;
        default: return GltfWrap::Repeat;
    }
}

float finite_number(const tinygltf::Value& v, float fallback) {
    if (!v.IsNumber()) return fallback;
    const auto x = static_cast<float>(v.GetNumberAsDouble());
    return std::isfinite(x) ? x : fallback;
}

// One textureInfo (index, texCoord, extensions) as a GltfTextureRef; an empty
// one when index is -1. A texture or image index out of range is an error.
GltfTextureRef texture_ref(const MaterialContext& c, int index, int texcoord, const tinygltf::ExtensionMap& extensions,
                           const char* slot) {
    GltfTextureRef ref;
    if (index < 0) return ref;
    const tinygltf::Model& m = c.model;
    if (static_cast<std::size_t>(index) >= m.textures.size())
        throw Error(c.file, c.what + ": " + slot + " names texture " + std::to_string(index) + ", but the file has " +
                                std::to_string(m.textures.size()));
    const tinygltf::Texture& t = m.textures[static_cast<std::size_t>(index)];
    ref.texture = index;
    ref.texcoord = std::max(texcoord, 0);
    // EXT_texture_webp's image is preferred: `source`, if any, is its
    // fallback for readers without WebP.
    int source = t.source;
    if (const auto webp = t.extensions.find(kWebp);
        webp != t.extensions.end() && webp->second.IsObject() && webp->second.Has("source"))
        source = value_int(webp->second.Get("source"), 0, INT_MAX).value_or(-1);
    if (source >= 0) {
        if (static_cast<std::size_t>(source) >= m.images.size())
            throw Error(c.file, "texture " + std::to_string(index) + " names image " + std::to_string(source) +
                                    ", but the file has " + std::to_string(m.images.size()));
        ref.image = source;
        ref.uri = m.images[static_cast<std::size_t>(source)].uri;
    }
    if (t.sampler >= 0) {
        if (static_cast<std::size_t>(t.sampler) >= m.samplers.size())
            throw Error(c.file, "texture " + std::to_string(index) + " names sampler " + std::to_string(t.sampler) +
                                    ", but the file has " + std::to_string(m.samplers.size()));
        const tinygltf::Sampler& s = m.samplers[static_cast<std::size_t>(t.sampler)];
        ref.wrap_s = wrap_mode(s.wrapS);
        ref.wrap_t = wrap_mode(s.wrapT);
    }
    if (const auto it = extensions.find(kTextureTransform); it != extensions.end() && it->second.IsObject()) {
        const tinygltf::Value& x = it->second;
        if (x.Has("offset") && x.Get("offset").ArrayLen() == 2)
            ref.offset = {finite_number(x.Get("offset").Get(0), 0), finite_number(x.Get("offset").Get(1), 0)};
        if (x.Has("scale") && x.Get("scale").ArrayLen() == 2)
            ref.scale = {finite_number(x.Get("scale").Get(0), 1), finite_number(x.Get("scale").Get(1), 1)};
        if (x.Has("rotation")) ref.rotation = finite_number(x.Get("rotation"), 0);
        if (x.Has("texCoord")) ref.texcoord = value_int(x.Get("texCoord"), 0, 255).value_or(ref.texcoord);
    }
    return ref;
}

// The number `name` of extension `extension` on the material, if present.
std::optional<double> extension_number(const tinygltf::Material& m, const char* extension, const char* name) {
    const auto it = m.extensions.find(extension);
    if (it == m.extensions.end() || !it->second.IsObject() || !it->second.Has(name)) return std::nullopt;
    const tinygltf::Value& v = it->second.Get(name);
    if (!v.IsNumber()) return std::nullopt;
    return v.GetNumberAsDouble();
}

// A textureInfo object inside an extension (which tinygltf leaves as a
// generic value) as a GltfTextureRef; an empty one when `name` is absent.
GltfTextureRef extension_texture_ref(const MaterialContext& c, const tinygltf::Value& extension, const char* name) {
    if (!extension.Has(name)) return {};
    const tinygltf::Value& info = extension.Get(name);
    const std::optional<int> index = info.IsObject() ? value_int(info.Get("index"), 0, 1 << 30) : std::nullopt;
    if (!index) throw Error(c.file, c.what + ": " + name + " needs a texture index");
    const std::optional<int> texcoord = info.Has("texCoord") ? value_int(info.Get("texCoord"), 0, 255) : 0;
    if (!texcoord) throw Error(c.file, c.what + ": " + name + " has a bad texCoord");
    tinygltf::ExtensionMap extensions;
    if (const tinygltf::Value& x = info.Get("extensions"); x.IsObject())
        for (const std::string& key : x.Keys()) extensions[key] = x.Get(key);
    return texture_ref(c, *index, *texcoord, extensions, name);
}

// KHR_materials_specular (Blender writes it on every material): the
// dielectric layer's strength in [0, 1] and its F0 colour, which may exceed
// 1 (the BSDF clamps f0 = F0(ior) · colour at 1), with their textures.
void read_specular(const MaterialContext& c, const tinygltf::Material& g, Material& m, GltfMaterialTextures& refs) {
    const auto it = g.extensions.find(kSpecular);
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const tinygltf::Value& x = it->second;
    const std::string where = std::string(kSpecular) + " ";
    if (x.Has("specularFactor")) {
        if (!x.Get("specularFactor").IsNumber())
            throw Error(c.file, c.what + ": " + where + "specularFactor must be a number");
        m.specular = clamped(c, x.Get("specularFactor").GetNumberAsDouble(), "specularFactor");
    }
    if (x.Has("specularColorFactor")) {
        const tinygltf::Value& v = x.Get("specularColorFactor");
        std::vector<double> rgb;
        for (int k = 0; v.IsArray() && k < static_cast<int>(v.ArrayLen()) && k < 3; ++k)
            if (v.Get(k).IsNumber()) rgb.push_back(v.Get(k).GetNumberAsDouble());
        if (!v.IsArray() || v.ArrayLen() != 3 || rgb.size() != 3)
            throw Error(c.file, c.what + ": " + where + "specularColorFactor must be 3 numbers");
        const Vec3 colour = read_colour(c, rgb, Vec3{1.0f}, "specularColorFactor");
        if (min_component(colour) < 0.0f) c.diag.warn(c.file, c.what + ": specularColorFactor below 0 clamped to 0");
        m.specular_color = max(colour, Vec3{0.0f});
    }
    refs.specular = extension_texture_ref(c, x, "specularTexture");
    refs.specular_color = extension_texture_ref(c, x, "specularColorTexture");
}

// The number `name` of extension object x, in [lo, hi], or `fallback` when
// absent; an error when it is not a number, a warning and the clamped value
// when outside.
float extension_factor(const MaterialContext& c, const tinygltf::Value& x, const char* extension, const char* name,
                       float fallback) {
    if (!x.Has(name)) return fallback;
    if (!x.Get(name).IsNumber()) throw Error(c.file, c.what + ": " + extension + " " + name + " must be a number");
    return clamped(c, x.Get(name).GetNumberAsDouble(), name);
}

// KHR_materials_transmission (Blender writes it for glass): the fraction of
// the light entering the base that goes through, and its texture (R).
void read_transmission(const MaterialContext& c, const tinygltf::Material& g, Material& m, GltfMaterialTextures& refs) {
    const auto it = g.extensions.find(kTransmission);
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    m.transmission = extension_factor(c, it->second, kTransmission, "transmissionFactor", 0.0f);
    refs.transmission = extension_texture_ref(c, it->second, "transmissionTexture");
}

// KHR_materials_volume: thicknessFactor > 0 makes the mesh a closed volume
// of the material's ior, with Beer–Lambert attenuation inside
// (attenuationColor, attenuationDistance). thicknessTexture is ignored
// (sombra traces the real path length inside; the texture only approximates
// it for rasterisers), with a warning.
void read_volume(const MaterialContext& c, const tinygltf::Material& g, Material& m) {
    const auto it = g.extensions.find(kVolume);
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const tinygltf::Value& x = it->second;
    const std::string where = c.what + ": " + kVolume + " ";
    if (x.Has("thicknessFactor")) {
        const tinygltf::Value& v = x.Get("thicknessFactor");
        const float thickness = v.IsNumber() ? static_cast<float>(v.GetNumberAsDouble()) : -1.0f;
        if (!std::isfinite(thickness) || thickness < 0.0f)
            throw Error(c.file, where + "thicknessFactor must be a finite number >= 0");
        m.thickness = thickness;
    }
    if (x.Has("attenuationDistance")) {
        const tinygltf::Value& v = x.Get("attenuationDistance");
        const float distance = v.IsNumber() ? static_cast<float>(v.GetNumberAsDouble()) : -1.0f;
        if (!(distance > 0.0f)) throw Error(c.file, where + "attenuationDistance must be a number > 0");
        m.attenuation_distance = distance;
    }
    if (x.Has("attenuationColor")) {
        const tinygltf::Value& v = x.Get("attenuationColor");
        std::vector<double> rgb;
        for (int k = 0; v.IsArray() && k < static_cast<int>(v.ArrayLen()) && k < 3; ++k)
            if (v.Get(k).IsNumber()) rgb.push_back(v.Get(k).GetNumberAsDouble());
        if (!v.IsArray() || v.ArrayLen() != 3 || rgb.size() != 3)
            throw Error(c.file, where + "attenuationColor must be 3 numbers");
        const Vec3 colour = read_colour(c, rgb, Vec3{1.0f}, "attenuationColor");
        m.attenuation_color = {clamped(c, colour.x, "attenuationColor"), clamped(c, colour.y, "attenuationColor"),
                               clamped(c, colour.z, "attenuationColor")};
    }
    if (x.Has("thicknessTexture"))
        c.diag.warn(c.file, where + "thicknessTexture ignored (the path length inside the mesh is traced)");
    if (m.thickness > 0.0f && !(m.transmission > 0.0f))
        c.diag.warn(c.file, where + "without transmission: the volume is never entered, and ignored");
}

// KHR_materials_clearcoat: the coat's strength (clearcoatTexture's R),
// roughness (clearcoatRoughnessTexture's G) and normal map
// (clearcoatNormalTexture, with its scale as normalTexture's).
void read_clearcoat(const MaterialContext& c, const tinygltf::Material& g, Material& m, GltfMaterialTextures& refs) {
    const auto it = g.extensions.find(kClearcoat);
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const tinygltf::Value& x = it->second;
    m.clearcoat = extension_factor(c, x, kClearcoat, "clearcoatFactor", 0.0f);
    m.clearcoat_roughness = extension_factor(c, x, kClearcoat, "clearcoatRoughnessFactor", 0.0f);
    refs.clearcoat = extension_texture_ref(c, x, "clearcoatTexture");
    refs.clearcoat_roughness = extension_texture_ref(c, x, "clearcoatRoughnessTexture");
    refs.clearcoat_normal = extension_texture_ref(c, x, "clearcoatNormalTexture");
    if (refs.clearcoat_normal.present())
        refs.clearcoat_normal.strength = finite_number(x.Get("clearcoatNormalTexture").Get("scale"), 1);
}

// KHR_materials_sheen: the fibre layer's colour (each channel in [0, 1],
// clamped with a warning outside) and roughness, with their textures
// (sheenColorTexture's sRGB RGB, sheenRoughnessTexture's A).
void read_sheen(const MaterialContext& c, const tinygltf::Material& g, Material& m, GltfMaterialTextures& refs) {
    const auto it = g.extensions.find(kSheen);
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const tinygltf::Value& x = it->second;
    if (x.Has("sheenColorFactor")) {
        const tinygltf::Value& v = x.Get("sheenColorFactor");
        std::vector<double> rgb;
        for (int k = 0; v.IsArray() && k < static_cast<int>(v.ArrayLen()) && k < 3; ++k)
            if (v.Get(k).IsNumber()) rgb.push_back(v.Get(k).GetNumberAsDouble());
        if (!v.IsArray() || v.ArrayLen() != 3 || rgb.size() != 3)
            throw Error(c.file, c.what + ": " + kSheen + " sheenColorFactor must be 3 numbers");
        const Vec3 colour = read_colour(c, rgb, Vec3{0.0f}, "sheenColorFactor");
        m.sheen_color = {clamped(c, colour.x, "sheenColorFactor"), clamped(c, colour.y, "sheenColorFactor"),
                         clamped(c, colour.z, "sheenColorFactor")};
    }
    m.sheen_roughness = extension_factor(c, x, kSheen, "sheenRoughnessFactor", 0.0f);
    refs.sheen_color = extension_texture_ref(c, x, "sheenColorTexture");
    refs.sheen_roughness = extension_texture_ref(c, x, "sheenRoughnessTexture");
}

}  // namespace

Materials convert_materials(const tinygltf::Model& model, const std::string& file, Diagnostics& diag) {
    Materials out;
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& g = model.materials[i];
        const MaterialContext c{model, file, "material " + std::to_string(i), diag};
        const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;

        Material m;
        m.name = g.name.empty() ? "gltf material " + std::to_string(i) : g.name;
        m.type = MaterialType::Pbr;
        const Vec3 base = read_colour(c, pbr.baseColorFactor, Vec3{1.0f}, "baseColorFactor");
        m.base_color = {clamped(c, base.x, "baseColorFactor"), clamped(c, base.y, "baseColorFactor"),
                        clamped(c, base.z, "baseColorFactor")};
        // The base colour doubles as the diffuse albedo for code that reads
        // kd regardless of the type (the version-1 BRDF terms).
        m.kd = m.base_color;
        m.metallic = clamped(c, pbr.metallicFactor, "metallicFactor");
        m.roughness = clamped(c, pbr.roughnessFactor, "roughnessFactor");
        // KHR_materials_ior allows ior = 1 (f0 = 0: no dielectric reflection
        // at normal incidence), and 0 (f0 = 1), with which KHR_materials_specular
        // converts specular-glossiness materials (their F0 is then the
        // specular colour alone); other values below 1 are outside its schema.
        if (const std::optional<double> ior = extension_number(g, kIor, "ior")) {
            if (std::isfinite(static_cast<float>(*ior)) && (*ior >= 1.0 || *ior == 0.0))
                m.ior = static_cast<float>(*ior);
            else
                diag.warn(file,
                          c.what + ": " + kIor + " ior " + format_number(*ior) + " is below 1 and not 0: 1.5 used");
        }
        const Vec3 emissive = read_colour(c, g.emissiveFactor, Vec3{0.0f}, "emissiveFactor");
        const float strength =
            static_cast<float>(extension_number(g, kEmissiveStrength, "emissiveStrength").value_or(1.0));
        if (!std::isfinite(strength) || strength < 0.0f)
            throw Error(file, c.what + ": emissiveStrength must be finite and >= 0");
        m.ke = max(emissive, Vec3{0.0f}) * strength;
        if (!is_finite(m.ke)) throw Error(file, c.what + ": emission is not finite");

        GltfMaterialTextures refs;
        refs.base_color = texture_ref(c, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                      pbr.baseColorTexture.extensions, "baseColorTexture");
        refs.metallic_roughness =
            texture_ref(c, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                        pbr.metallicRoughnessTexture.extensions, "metallicRoughnessTexture");
        refs.normal = texture_ref(c, g.normalTexture.index, g.normalTexture.texCoord, g.normalTexture.extensions,
                                  "normalTexture");
        refs.normal.strength = finite_number(tinygltf::Value(g.normalTexture.scale), 1);
        refs.emissive = texture_ref(c, g.emissiveTexture.index, g.emissiveTexture.texCoord,
                                    g.emissiveTexture.extensions, "emissiveTexture");
        refs.occlusion = texture_ref(c, g.occlusionTexture.index, g.occlusionTexture.texCoord,
                                     g.occlusionTexture.extensions, "occlusionTexture");
        refs.occlusion.strength = finite_number(tinygltf::Value(g.occlusionTexture.strength), 1);
        read_specular(c, g, m, refs);
        read_transmission(c, g, m, refs);
        read_volume(c, g, m);
        read_clearcoat(c, g, m, refs);
        read_sheen(c, g, m, refs);
        // KHR_materials_unlit: emission only. The base colour (factor times
        // texture) becomes the emitted radiance of a black diffuse surface,
        // lit by nothing and, as any emitter in a path tracer, lighting
        // what it faces; the other parameters and COLOR_0 do not apply.
        if (g.extensions.count(kUnlit) > 0) {
            m.type = MaterialType::Diffuse;
            m.kd = Vec3{0.0f};
            m.ke = m.base_color;
            refs.emissive = refs.base_color;
            refs.metallic_roughness = {};
            refs.normal = {};
            refs.clearcoat_normal = {};
        }
        refs.alpha_mode = g.alphaMode == "MASK"    ? AlphaMode::Mask
                          : g.alphaMode == "BLEND" ? AlphaMode::Blend
                                                   : AlphaMode::Opaque;
        refs.alpha_cutoff = finite_number(tinygltf::Value(g.alphaCutoff), 0.5f);
        refs.base_alpha =
            pbr.baseColorFactor.size() == 4 ? finite_number(tinygltf::Value(pbr.baseColorFactor[3]), 1) : 1;
        out.materials.push_back(std::move(m));
        out.texture_refs.push_back(std::move(refs));
    }
    return out;
}

std::optional<PunctualLight> punctual_light(const tinygltf::Model& model, int index, const std::string& file,
                                            std::string& skipped_type, Diagnostics& diag) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.lights.size())
        throw Error(file, std::string(kLights) + ": a node names light " + std::to_string(index) +
                              ", but the file has " + std::to_string(model.lights.size()));
    const tinygltf::Light& light = model.lights[static_cast<std::size_t>(index)];
    if (light.type != "point" && light.type != "spot" && light.type != "directional") {
        skipped_type = light.type.empty() ? "untyped" : light.type;
        return std::nullopt;
    }
    const std::string what = std::string(kLights) + " light " + std::to_string(index);
    Vec3 colour{1.0f};
    if (!light.color.empty()) {
        if (light.color.size() != 3) throw Error(file, what + ": color must have 3 components");
        colour = {float(light.color[0]), float(light.color[1]), float(light.color[2])};
    }
    // Candela (point, spot) or lux (directional) to watts, as Blender imports them.
    const Vec3 intensity = colour * static_cast<float>(light.intensity) / kLumensPerWatt;
    if (!is_finite(intensity) || min_component(colour) < 0.0f || light.intensity < 0.0)
        throw Error(file, what + ": color and intensity must be finite and >= 0");
    // Every light looks down its node's −z axis; the node's transform places it.
    const Vec3 down_z{0, 0, -1};
    if (light.type == "point") return make_point_light(Vec3{0.0f}, intensity);
    if (light.type == "directional") return make_directional_light(down_z, intensity);

    double inner = light.spot.innerConeAngle, outer = light.spot.outerConeAngle;
    constexpr double kHalfPi = std::numbers::pi / 2;
    if (!(outer > 0.0 && outer <= kHalfPi))
        throw Error(file, what + ": spot.outerConeAngle must lie in (0, pi/2], not " + format_number(outer));
    if (!(inner >= 0.0)) throw Error(file, what + ": spot.innerConeAngle must be >= 0, not " + format_number(inner));
    if (inner >= outer) {
        // Blender writes equal angles for a spot without blend (spec §16).
        if (inner > outer)
            diag.warn(file, what + ": spot.innerConeAngle " + format_number(inner) + " >= outerConeAngle " +
                                format_number(outer) + ", read as equal");
        inner = outer;
    }
    constexpr double kDegrees = 180.0 / std::numbers::pi;
    return make_spot_light(Vec3{0.0f}, down_z, intensity, static_cast<float>(outer * kDegrees),
                           static_cast<float>(inner * kDegrees));
}

}  // namespace sombra::gltf
