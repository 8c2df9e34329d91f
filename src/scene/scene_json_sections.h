// Private to the scene loader: the sections of a scene file (spec §2, §3, §5,
// §8), each read and validated on its own. Every function throws Error naming
// the JSON pointer of the offending value.
#pragma once

#include <string_view>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_json_read.h"
#include "scene/transform.h"

namespace sombra {

// "render": {width, height, spp, seed}; absent members keep their defaults.
RenderSettings read_render(const SceneJson& s, const Json& v, std::string_view pointer);

// "camera": exactly one of the basis form (origin, left, up, forward: non-zero,
// mutually perpendicular) and the look-at form (origin, look_at, up, fov).
CameraSpec read_camera(const SceneJson& s, const Json& v, std::string_view pointer);

// "materials": {name: {type, kd, ks, shininess, ke}}, in name order. Warns
// when kd + ks exceeds 1 in a channel (not energy conserving).
std::vector<Material> read_materials(const SceneJson& s, const Json& v, std::string_view pointer);

// "lights": [{type, position, intensity}]; "type" may be left out ("point" is
// the only kind).
std::vector<PointLight> read_lights(const SceneJson& s, const Json& v, std::string_view pointer);

// "transform": a list of steps, the first listed acting first. The result is
// finite and invertible.
Transform read_transform(const SceneJson& s, const Json& v, std::string_view pointer);

}  // namespace sombra
