// The viewer's camera (spec §20): the look-at form of spec §3 that the page
// orbits, pans and zooms, checked as the scene file checks its camera.
#pragma once

#include <optional>
#include <string>

#include "render/camera.h"
#include "scene/scene.h"

namespace sombra {

// The look-at camera the page starts from: the scene's own when it is
// written in that form, else one read off the resolved `camera` (origin,
// a point one unit ahead, its up axis and vertical field of view; an
// orthographic camera's fov is unused, its zoom is the spec's
// ortho_half_height). The scene's camera is rendered as written until the
// page sends another.
CameraLookAt view_camera_of(const CameraSpec& spec, const Camera& camera);

// "" when `camera` is one the scene file would accept (finite numbers,
// look_at away from origin, up neither zero nor parallel to the view, fov
// strictly between 0 and 180 degrees), else what is wrong, e.g.
// "fov must lie strictly between 0 and 180 degrees".
std::string view_camera_problem(const CameraLookAt& camera);

// "" when `half_height` can be an orthographic camera's half-height (a
// positive finite number, as glTF's ymag), else what is wrong.
std::string view_half_height_problem(double half_height);

// The scene's camera with `camera` as its look-at form; the lens (aperture
// and focus distance) and the projection stay the scene's. An orthographic
// camera takes `half_height` as its view's half-height when given: its
// zoom, where a perspective camera's is the distance to look_at.
CameraSpec with_view_camera(const CameraSpec& scene_camera, const CameraLookAt& camera,
                            std::optional<float> half_height = std::nullopt);

}  // namespace sombra
