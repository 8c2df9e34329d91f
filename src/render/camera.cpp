#include "render/camera.h"

#include <cmath>
#include <numbers>

#include "core/vec3d.h"

namespace sombra {

namespace {

Vec3d scaled_unit(Vec3d a, double length) {
    const double s = length / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return {a.x * s, a.y * s, a.z * s};
}

}  // namespace

namespace {

// The pinhole basis of either form.
Camera make_pinhole(const CameraSpec& spec, int width, int height) {
    if (spec.basis) return Camera{spec.basis->origin, spec.basis->left, spec.basis->up, spec.basis->forward};

    // Look-at form, computed in double so that the basis is perpendicular to
    // float precision: f = normalize(c − o), l = normalize(up × f)·tan(fov/2)·aspect,
    // u = normalize(f × l)·tan(fov/2).
    const CameraLookAt& look = *spec.look_at;
    const Vec3d o = to_double(look.origin);
    const Vec3d c = to_double(look.look_at);
    const double aspect = static_cast<double>(width) / static_cast<double>(height);
    const double half_height = std::tan(static_cast<double>(look.fov_degrees) * std::numbers::pi / 360.0);
    const Vec3d f = scaled_unit(c - o, 1.0);
    const Vec3d l = scaled_unit(cross(to_double(look.up), f), half_height * aspect);
    const Vec3d u = scaled_unit(cross(f, l), half_height);
    return Camera{look.origin, to_float(l), to_float(u), to_float(f)};
}

// The orthographic basis of either form: l and u scaled to the view's
// half-width and half-height, f unit.
Camera make_orthographic(const CameraSpec& spec, int width, int height) {
    const double aspect = static_cast<double>(width) / static_cast<double>(height);
    const double half_height = spec.ortho_half_height;
    Vec3d f, up;
    if (spec.basis) {
        f = to_double(spec.basis->forward);
        up = to_double(spec.basis->up);
    } else {
        f = to_double(spec.look_at->look_at) - to_double(spec.look_at->origin);
        up = to_double(spec.look_at->up);
    }
    f = scaled_unit(f, 1.0);
    const Vec3d l = scaled_unit(cross(up, f), half_height * aspect);
    const Vec3d u = scaled_unit(cross(f, l), half_height);
    Camera camera{spec.basis ? spec.basis->origin : spec.look_at->origin, to_float(l), to_float(u), to_float(f)};
    camera.orthographic = true;
    return camera;
}

}  // namespace

Camera make_camera(const CameraSpec& spec, int width, int height) {
    // Parallel rays have no lens: a glTF orthographic camera has no aperture.
    if (spec.projection == CameraSpec::Projection::Orthographic) return make_orthographic(spec, width, height);
    Camera camera = make_pinhole(spec, width, height);
    if (!(spec.aperture_radius > 0.0f)) return camera;
    const double r = spec.aperture_radius;
    camera.lens_radius = spec.aperture_radius;
    camera.lens_left = to_float(scaled_unit(to_double(camera.left), r));
    camera.lens_up = to_float(scaled_unit(to_double(camera.up), r));
    camera.unit_forward = to_float(scaled_unit(to_double(camera.forward), 1.0));
    // Readers require focus_distance with the basis form; |forward| keeps a
    // scene built in code without one well defined.
    if (spec.focus_distance)
        camera.focus_distance = *spec.focus_distance;
    else if (spec.look_at)
        camera.focus_distance =
            static_cast<float>(length(to_double(spec.look_at->look_at) - to_double(spec.look_at->origin)));
    else
        camera.focus_distance = static_cast<float>(length(to_double(camera.forward)));
    return camera;
}

}  // namespace sombra
