// The film: linear RGB radiance per pixel, the renderer's output.
#pragma once

#include <cstddef>
#include <vector>

#include "core/vec3.h"

namespace sombra {

struct Film {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // row-major, top row first, 3 floats per pixel

    Film() = default;
    Film(int w, int h)
        : width(w), height(h), rgb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, 0.0f) {}

    void set(int i, int j, Vec3 v) {
        float* p =
            &rgb[(static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)) * 3];
        p[0] = v.x;
        p[1] = v.y;
        p[2] = v.z;
    }
    Vec3 at(int i, int j) const {
        const float* p =
            &rgb[(static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)) * 3];
        return {p[0], p[1], p[2]};
    }
};

}  // namespace sombra
