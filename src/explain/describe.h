// Words and numbers shared by explain's text, JSON and SVG: how a material,
// an object or a light's outcome is named.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "render/sample_record.h"
#include "scene/scene.h"

namespace sombra {

// "diffuse", "phong", "mirror", "dielectric", "conductor", "pbr".
std::string material_type_name(MaterialType type);

// A material's parameters as (name, value) pairs in the order spec §5/§11 list them.
struct MaterialParameter {
    std::string name;
    std::vector<float> value;  // one number, or three for RGB
};
std::vector<MaterialParameter> material_parameters(const Material& m);

// Where triangle `triangle` of surface_mesh(scene, instance) came from.
struct TriangleOrigin {
    std::string object;                     // "/objects/2", "/lights/0", or "?" when unknown
    std::string file;                       // the mesh file ("" for a quad light)
    std::uint32_t triangle = 0;             // index among that object's triangles (its mesh's, in an instance)
    std::optional<std::uint32_t> instance;  // in an instanced object: which of its instances (from 0)
    std::string material;                   // the triangle's material's name
};
TriangleOrigin triangle_origin(const Scene& scene, std::uint32_t triangle, std::uint32_t instance = kNoInstance);
// "…, instance 3" for a triangle in an instance; "" otherwise.
std::string instance_words(const TriangleOrigin& origin);

// "behind", "on_surface", "outside_cone", "blocked", "visible".
const char* outcome_name(LightOutcome outcome);
// "point", "spot", "directional".
const char* light_type_name(LightType type);

// A number for reading: 4 significant digits ("0.1592", "1.2e+05").
std::string readable(float v);
// A vector for reading: "(0.1592, 0, 1)".
std::string readable(Vec3 v);
// The exact float, shortest text that reads back to it.
std::string exact(float v);
std::string exact(Vec3 v);

}  // namespace sombra
