// Two-component float vector: texture coordinates.
#pragma once

namespace sombra {

struct Vec2 {
    float x = 0, y = 0;
    constexpr bool operator==(const Vec2&) const = default;
};

}  // namespace sombra
