#include "view/view_camera.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/vec3d.h"

namespace sombra {

namespace {

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

CameraLookAt view_camera_of(const CameraSpec& spec, const Camera& camera) {
    if (spec.look_at) return *spec.look_at;
    CameraLookAt c;
    c.origin = camera.origin;
    const float forward = length(camera.forward);
    c.look_at = camera.origin + camera.forward / forward;
    c.up = camera.up / length(camera.up);
    // An orthographic camera has no field of view (its |up| is the
    // half-height): the default stays, unused.
    if (!camera.orthographic)
        c.fov_degrees =
            static_cast<float>(2.0 * std::atan(double{length(camera.up)} / forward) * 180.0 / std::numbers::pi);
    return c;
}

std::string view_camera_problem(const CameraLookAt& c) {
    if (!finite(c.origin) || !finite(c.look_at) || !finite(c.up) || !std::isfinite(c.fov_degrees))
        return "camera values must be finite numbers";
    const Vec3d view = to_double(c.look_at) - to_double(c.origin);
    const Vec3d up = to_double(c.up);
    if (length(view) == 0 || length(c.look_at - c.origin) == 0) return "'look_at' is the same point as 'origin'";
    if (length(up) == 0) return "camera vector 'up' is zero";
    // Parallel within a millionth of a radian: the basis would not survive float normalisation.
    if (length(cross(view, up)) <= 1e-6 * length(view) * length(up))
        return "'up' is parallel to the view direction ('look_at' - 'origin')";
    if (!(c.fov_degrees > 0 && c.fov_degrees < 180)) return "fov must lie strictly between 0 and 180 degrees";
    return {};
}

std::string view_half_height_problem(double half_height) {
    if (!(half_height > 0) || !(half_height <= std::numeric_limits<float>::max()))
        return "half_height must be a positive finite number";
    return {};
}

CameraSpec with_view_camera(const CameraSpec& scene_camera, const CameraLookAt& camera,
                            std::optional<float> half_height) {
    CameraSpec spec = scene_camera;
    spec.basis.reset();
    spec.look_at = camera;
    if (half_height && spec.projection == CameraSpec::Projection::Orthographic) spec.ortho_half_height = *half_height;
    return spec;
}

}  // namespace sombra
