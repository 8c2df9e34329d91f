// The viewer's camera (spec §20): the look-at form of spec §3 that the page
// orbits, pans and zooms, checked as the scene file checks its camera.
#pragma once

#include <string>

#include "render/camera.h"
#include "scene/scene.h"

namespace sombra {

// The look-at camera the page starts from: the scene's own when it is
// written in that form, else one read off the resolved `camera` (origin,
// a point one unit ahead, its up axis and vertical field of view). The
// scene's camera is rendered as written until the page sends another.
CameraLookAt view_camera_of(const CameraSpec& spec, const Camera& camera);

// "" when `camera` is one the scene file would accept (finite numbers,
// look_at away from origin, up neither zero nor parallel to the view, fov
// strictly between 0 and 180 degrees), else what is wrong, e.g.
// "fov must lie strictly between 0 and 180 degrees".
std::string view_camera_problem(const CameraLookAt& camera);

// The scene's camera with `camera` as its look-at form; the lens (aperture
// and focus distance) stays the scene's.
CameraSpec with_view_camera(const CameraSpec& scene_camera, const CameraLookAt& camera);

}  // namespace sombra
