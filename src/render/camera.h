// The camera of spec §3, always in the assignment's basis form: M = [l u f o]
// maps image-plane coordinates (s, t) ∈ [-1, 1]² to the point s·l + t·u +
// f + o, and the pinhole ray for (s, t) leaves o towards it; with a thin
// lens (spec §17) rays leave points of the lens and meet on the focus plane.
#pragma once

#include <cmath>

#include "core/ray.h"
#include "scene/scene.h"

namespace sombra {

struct Camera {
    Vec3 origin;
    Vec3 left;     // s = +1 is the image's left edge; |left| sets the horizontal field of view
    Vec3 up;       // t = +1 is the top edge; |up| sets the vertical field of view
    Vec3 forward;  // from the origin to the image plane's centre
    // Thin lens (spec §17): lens_radius 0 is the pinhole. lens_left and
    // lens_up are the unit left and up vectors times lens_radius;
    // unit_forward is forward / |forward|.
    float lens_radius = 0;
    float focus_distance = 1;
    Vec3 lens_left{0.0f}, lens_up{0.0f}, unit_forward{0.0f};
    // Orthographic (spec §24): the ray for (s, t) leaves o + s·l + t·u along
    // forward (unit), so |left| and |up| are the view's half-width and
    // half-height; never with a lens (lens_radius 0).
    bool orthographic = false;
};

// Resolves either form of the scene's camera. The look-at form depends on the
// image's aspect ratio (width / height); the basis form ignores the size, so
// changing the resolution never changes its rays. The spec must have been
// validated (scene_file.h does), exactly one form set.
Camera make_camera(const CameraSpec& spec, int width, int height);

// The pinhole ray through image-plane point (s, t); its direction is not
// normalised. An orthographic camera's ray for (s, t) starts where the
// pinhole's image-plane offset s·l + t·u puts it, so both see the image the
// same way round.
inline Ray camera_ray(const Camera& camera, float s, float t) {
    const Vec3 offset = s * camera.left + t * camera.up;
    if (camera.orthographic) return Ray{camera.origin + offset, camera.forward};
    return Ray{camera.origin, offset + camera.forward};
}

// A point on the unit disc from (u1, u2) ∈ [0, 1)², by Shirley and Chiu's
// concentric map (area-preserving, so uniform samples stay uniform and
// stratified ones stay stratified).
inline void concentric_disc(float u1, float u2, float& x, float& y) {
    const float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f) {
        x = y = 0.0f;
        return;
    }
    constexpr float kQuarterPi = 0.78539816339744830962f;
    if (std::fabs(a) > std::fabs(b)) {
        x = a * std::cos(kQuarterPi * (b / a));
        y = a * std::sin(kQuarterPi * (b / a));
    } else {
        x = b * std::sin(kQuarterPi * (a / b));
        y = b * std::cos(kQuarterPi * (a / b));
    }
}

// The ray through (s, t) for lens sample (u1, u2): from the lens point
// o + r·(x·l̂ + y·û), (x, y) = concentric_disc(u1, u2), through the point
// where the pinhole ray crosses the focus plane. Its direction is scaled so
// that its forward component equals the pinhole ray's (the two coincide at
// the lens centre). With lens_radius 0 exactly camera_ray(camera, s, t).
inline Ray camera_ray(const Camera& camera, float s, float t, float u1, float u2) {
    const Ray pinhole = camera_ray(camera, s, t);
    if (!(camera.lens_radius > 0.0f)) return pinhole;
    float x = 0, y = 0;
    concentric_disc(u1, u2, x, y);
    const Vec3 offset = x * camera.lens_left + y * camera.lens_up;
    // The pinhole ray meets the focus plane at o + d·(focus / (d·f̂)); from
    // o + offset toward it is d·(focus / (d·f̂)) − offset, here times (d·f̂) / focus.
    const float along = dot(pinhole.dir, camera.unit_forward);
    return Ray{camera.origin + offset, pinhole.dir - offset * (along / camera.focus_distance)};
}

// Image-plane coordinates of a point in the image given in pixel units:
// x ∈ [0, W] from the left edge, y ∈ [0, H] from the top edge. The centre of
// pixel (i, j) is x = i + 0.5, y = j + 0.5, i.e. s = 1 − (2i + 1)/W and
// t = 1 − (2j + 1)/H.
inline float image_plane_s(float x, int width) { return 1.0f - 2.0f * x / static_cast<float>(width); }
inline float image_plane_t(float y, int height) { return 1.0f - 2.0f * y / static_cast<float>(height); }

}  // namespace sombra
