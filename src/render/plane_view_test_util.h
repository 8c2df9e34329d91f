// Test helper: a camera looking straight down at the plane y = 0, and where
// each pixel's centre ray meets that plane, for closed-form image tests.
#pragma once

#include "render/camera.h"

namespace sombra::testing {

// A camera at height `eye` looking straight down at the plane y = 0.
inline Camera camera_looking_down(float eye, float half_extent) {
    return Camera{{0, eye, 0}, {-half_extent, 0, 0}, {0, 0, -half_extent}, {0, -1, 0}};
}

// Where the ray through pixel (i, j)'s centre meets the plane y = 0 (computed in double).
inline void plane_hit(const Camera& c, int i, int j, int w, int h, double& x, double& z) {
    const double s = 1.0 - (2.0 * i + 1.0) / w, t = 1.0 - (2.0 * j + 1.0) / h;
    const double dx = s * c.left.x + t * c.up.x + c.forward.x;
    const double dy = s * c.left.y + t * c.up.y + c.forward.y;
    const double dz = s * c.left.z + t * c.up.z + c.forward.z;
    const double k = -static_cast<double>(c.origin.y) / dy;
    x = c.origin.x + k * dx;
    z = c.origin.z + k * dz;
}

}  // namespace sombra::testing
