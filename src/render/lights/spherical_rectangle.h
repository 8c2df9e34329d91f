// Directions toward a rectangle, uniformly distributed over the solid angle
// it subtends (Ureña, Fajardo and King 2013, "An Area-Preserving
// Parametrization for Spherical Rectangles"), as Cycles samples its area
// lights. A quad light sampled this way is one light whose density is 1/Ω
// everywhere on it, and a 2-D sample point keeps its stratification over
// the whole rectangle; as two spherical triangles (render/lights/spherical_triangle.h)
// it took a choice between halves whose densities differ.
#pragma once

#include "core/vec3.h"
#include "core/vec3d.h"

namespace sombra {

// The rectangle corner + s·edge1 + t·edge2 (s, t in [0, 1], edge1 ⟂ edge2)
// seen from x, in the local frame the parametrisation needs: x at the
// origin, the rectangle in the plane z = z0 < 0 spanning [x0, x1] × [y0, y1].
// Computed in double: the solid angle is a sum of four angles less 2π.
struct SphericalRectangle {
    Vec3d origin{}, ex{}, ey{}, ez{};  // x and the frame's unit axes (ez away from the rectangle)
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0, z0 = 0;
    double b0 = 0, b1 = 0, k = 0;  // the parametrisation's constants
    double solid_angle = 0;        // Ω; 0 when degenerate or seen edge-on
};

SphericalRectangle make_spherical_rectangle(Vec3 x, Vec3 corner, Vec3 edge1, Vec3 edge2);

// The point of the rectangle in direction of a sample uniform over its solid
// angle, for (u1, u2) uniform in [0, 1)²; r.solid_angle must be > 0.
Vec3 sample_spherical_rectangle(const SphericalRectangle& r, float u1, float u2);

}  // namespace sombra
