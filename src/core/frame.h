// An orthonormal frame (s, t, n) around a unit normal: BSDFs work in it, with
// the normal as +z, so that cos θ is just a vector's z.
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace sombra {

struct Frame {
    Vec3 s, t, n;

    // A right-handed frame with n as its third axis; n must be unit length.
    // Branchless construction of Duff et al. 2017 ("Building an Orthonormal
    // Basis, Revisited"): continuous everywhere except at n.z = 0's sign flip.
    static Frame from_normal(Vec3 n) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        return Frame{Vec3{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, Vec3{b, sign + n.y * n.y * a, -n.y}, n};
    }

    Vec3 to_local(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 to_world(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace sombra
