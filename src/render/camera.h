// The pinhole camera of spec §3, always in the assignment's basis form:
// M = [l u f o] maps image-plane coordinates (s, t) ∈ [-1, 1]² to the point
// s·l + t·u + f + o, and the ray for (s, t) leaves o towards it.
#pragma once

#include "core/ray.h"
#include "scene/scene.h"

namespace sombra {

struct Camera {
    Vec3 origin;
    Vec3 left;     // s = +1 is the image's left edge; |left| sets the horizontal field of view
    Vec3 up;       // t = +1 is the top edge; |up| sets the vertical field of view
    Vec3 forward;  // from the origin to the image plane's centre
};

// Resolves either form of the scene's camera. The look-at form depends on the
// image's aspect ratio (width / height); the basis form ignores the size, so
// changing the resolution never changes its rays. The spec must have been
// validated (scene_file.h does), exactly one form set.
Camera make_camera(const CameraSpec& spec, int width, int height);

// The ray through image-plane point (s, t); its direction is not normalised.
inline Ray camera_ray(const Camera& camera, float s, float t) {
    return Ray{camera.origin, s * camera.left + t * camera.up + camera.forward};
}

// Image-plane coordinates of a point in the image given in pixel units:
// x ∈ [0, W] from the left edge, y ∈ [0, H] from the top edge. The centre of
// pixel (i, j) is x = i + 0.5, y = j + 0.5, i.e. s = 1 − (2i + 1)/W and
// t = 1 − (2j + 1)/H.
inline float image_plane_s(float x, int width) { return 1.0f - 2.0f * x / static_cast<float>(width); }
inline float image_plane_t(float y, int height) { return 1.0f - 2.0f * y / static_cast<float>(height); }

}  // namespace sombra
