// What a glTF node carries besides a mesh, placed by the node (spec §13,
// §16, §24): a camera, perspective or orthographic, and a
// KHR_lights_punctual light, in the file's coordinates.
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "core/format.h"
#include "io/gltf/gltf.h"
#include "io/mesh_file.h"
#include "scene/gltf_animation.h"

namespace sombra::gltf {

std::optional<ModelCamera> place_camera(const tinygltf::Model& model, int index, const Transform& world,
                                        const std::string& file, Diagnostics& diag) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.cameras.size())
        throw Error(file, "a node names camera " + std::to_string(index) + ", but the file has " +
                              std::to_string(model.cameras.size()));
    const tinygltf::Camera& c = model.cameras[std::size_t(index)];
    const bool orthographic = c.type == "orthographic";
    if (c.type != "perspective" && !orthographic) {
        diag.warn(file, "camera " + std::to_string(index) + " is " + c.type +
                            ", neither perspective nor orthographic: the model is framed automatically");
        return std::nullopt;
    }
    if (orthographic && !(std::isfinite(c.orthographic.ymag) && c.orthographic.ymag > 0))
        throw Error(file, "/cameras/" + std::to_string(index) +
                              "/orthographic/ymag: the view's half-height must be a finite number above 0, got " +
                              format_number(c.orthographic.ymag));
    ModelCamera cam;
    const bool placed = gltf_camera_frame(world, cam.origin, cam.forward, cam.up);
    if (orthographic) {
        cam.ymag = static_cast<float>(c.orthographic.ymag);
        if (!std::isfinite(cam.ymag))
            throw Error(file, "/cameras/" + std::to_string(index) +
                                  "/orthographic/ymag: " + format_number(c.orthographic.ymag) + " is too large");
    } else {
        const double yfov = c.perspective.yfov * 180.0 / std::numbers::pi;
        cam.yfov_degrees = static_cast<float>(yfov);
        cam.aspect = c.perspective.aspectRatio > 0 ? static_cast<float>(c.perspective.aspectRatio) : 0.0f;
        if (!(yfov > 0 && yfov < 180) || !std::isfinite(cam.aspect)) {
            diag.warn(file, "camera " + std::to_string(index) +
                                " is unusable (field of view or aspect): the model is framed automatically");
            return std::nullopt;
        }
    }
    if (!placed) {
        diag.warn(file, "camera " + std::to_string(index) +
                            " is unusable (its placement): the model is framed automatically");
        return std::nullopt;
    }
    return cam;
}

std::optional<PunctualLight> place_light(const tinygltf::Model& model, const tinygltf::Node& node, int node_index,
                                         const Transform& world, const std::string& file, Diagnostics& diag,
                                         std::map<std::string, std::size_t>& skipped, PunctualLight& in_node) {
    const auto it = node.extensions.find(kLights);
    if (it == node.extensions.end() || !it->second.IsObject()) return std::nullopt;
    const std::string name = "node " + std::to_string(node_index);
    const std::optional<int> index =
        it->second.Has("light") ? value_int(it->second.Get("light"), 0, 1 << 30) : std::nullopt;
    if (!index) throw Error(file, name + ": " + kLights + " names no light");
    std::string type;
    std::optional<PunctualLight> light = punctual_light(model, *index, file, type, diag);
    if (!light) {
        ++skipped[type + " lights"];
        return std::nullopt;
    }
    in_node = *light;
    switch (transform_light(*light, world)) {
        case LightPlacement::Ok: break;
        case LightPlacement::NonFinitePosition: throw Error(file, name + ": its light's position is not finite");
        case LightPlacement::NonFiniteDirection: throw Error(file, name + ": its light's direction is not finite");
    }
    return light;
}

}  // namespace sombra::gltf
