#include "explain/describe.h"

#include <cstdio>

#include "core/format.h"

namespace sombra {

std::string material_type_name(MaterialType type) {
    switch (type) {
        case MaterialType::Diffuse: return "diffuse";
        case MaterialType::Phong: return "phong";
        case MaterialType::Mirror: return "mirror";
        case MaterialType::Dielectric: return "dielectric";
        case MaterialType::Conductor: return "conductor";
        case MaterialType::Pbr: return "pbr";
        case MaterialType::Interface: return "interface";
    }
    return "?";
}

std::vector<MaterialParameter> material_parameters(const Material& m) {
    auto rgb = [](Vec3 v) { return std::vector<float>{v.x, v.y, v.z}; };
    std::vector<MaterialParameter> p;
    switch (m.type) {
        case MaterialType::Diffuse: p = {{"kd", rgb(m.kd)}}; break;
        case MaterialType::Phong: p = {{"kd", rgb(m.kd)}, {"ks", rgb(m.ks)}, {"shininess", {m.shininess}}}; break;
        case MaterialType::Mirror: p = {{"kr", rgb(m.kr)}}; break;
        case MaterialType::Dielectric: p = {{"ior", {m.ior}}, {"kt", rgb(m.kt)}}; break;
        case MaterialType::Conductor: p = {{"ks", rgb(m.ks)}, {"roughness", {m.roughness}}}; break;
        case MaterialType::Pbr:
            p = {{"base_color", rgb(m.base_color)},
                 {"metallic", {m.metallic}},
                 {"roughness", {m.roughness}},
                 {"ior", {m.ior}}};
            break;
        case MaterialType::Interface: break;
    }
    if (is_emissive(m)) p.push_back({"ke", rgb(m.ke)});
    return p;
}

TriangleOrigin triangle_origin(const Scene& scene, std::uint32_t triangle, std::uint32_t instance) {
    const TriangleMesh& mesh = surface_mesh(scene, instance);
    const std::string material =
        triangle < mesh.material_ids.size() ? scene.materials[mesh.material_ids[triangle]].name : std::string("?");
    if (instance != kNoInstance) {
        const SceneObject& object = scene.objects[scene.instances[instance].object];
        return {object.name, object.file, triangle, instance - object.first_instance, material};
    }
    const SceneObject* object = object_of_triangle(scene, triangle);
    if (!object) return {"?", "", triangle, std::nullopt, material};
    return {object->name, object->file, triangle - object->first_triangle, std::nullopt, material};
}

std::string instance_words(const TriangleOrigin& origin) {
    return origin.instance ? ", instance " + std::to_string(*origin.instance) : std::string();
}

const char* light_type_name(LightType type) { return light_type_traits(type).name; }

const char* outcome_name(LightOutcome outcome) {
    switch (outcome) {
        case LightOutcome::Behind: return "behind";
        case LightOutcome::OnSurface: return "on_surface";
        case LightOutcome::OutsideCone: return "outside_cone";
        case LightOutcome::Blocked: return "blocked";
        case LightOutcome::Visible: return "visible";
    }
    return "?";
}

std::string readable(float v) {
    if (v == 0.0f) return "0";  // also −0: a learner need not meet signed zeros
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", static_cast<double>(v));
    return buf;
}

std::string readable(Vec3 v) {
    // append, not "(" + std::string: GCC 12's false -Wrestrict (bug 105329).
    return std::string("(")
        .append(readable(v.x))
        .append(", ")
        .append(readable(v.y))
        .append(", ")
        .append(readable(v.z))
        .append(")");
}

std::string exact(float v) { return format_number(v); }

std::string exact(Vec3 v) {
    return std::string("(")
        .append(exact(v.x))
        .append(", ")
        .append(exact(v.y))
        .append(", ")
        .append(exact(v.z))
        .append(")");
}

}  // namespace sombra
