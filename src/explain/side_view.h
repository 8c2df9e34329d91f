// The view explain's picture shows the scene from: orthographic, from above,
// to the right of and behind the camera, so that nothing hides anything and
// the path reads left to right.
#pragma once

#include <algorithm>

#include "core/vec3.h"
#include "render/camera.h"

namespace sombra {

// A point of the view's plane, or of the picture (SVG units, y down).
struct Point2 {
    float x, y;
};

class SideView {
public:
    explicit SideView(const Camera& camera) {
        const Vec3 f = normalize(camera.forward), u = normalize(camera.up), l = normalize(camera.left);
        dir_ = normalize(0.9f * l - 0.6f * u + 0.5f * f);  // looking from the right (−l), above and behind
        up_ = normalize(u - dot(u, dir_) * dir_);
        right_ = cross(dir_, up_);
    }
    Vec3 direction() const { return dir_; }
    Point2 flat(Vec3 p) const { return {dot(p, right_), dot(p, up_)}; }

    // Chooses scale and offset so that [lo, hi] (in flat coordinates) fills
    // a panel `width` × `height` less `margin` on each side.
    void fit(Point2 lo, Point2 hi, float width, float height, float margin) {
        const float w = std::max(hi.x - lo.x, 1e-6f), h = std::max(hi.y - lo.y, 1e-6f);
        scale_ = std::min((width - 2 * margin) / w, (height - 2 * margin) / h);
        ox_ = width * 0.5f - scale_ * (lo.x + hi.x) * 0.5f;
        oy_ = height * 0.5f + scale_ * (lo.y + hi.y) * 0.5f;
        extent_ = std::max(w, h);
    }
    Point2 screen(Vec3 p) const {
        const Point2 q = flat(p);
        return {ox_ + scale_ * q.x, oy_ - scale_ * q.y};
    }
    float extent() const { return extent_; }  // the fitted region's size in world units

private:
    Vec3 dir_, up_, right_;
    float scale_ = 1, ox_ = 0, oy_ = 0, extent_ = 1;
};

}  // namespace sombra
