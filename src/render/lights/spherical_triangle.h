// Directions toward a triangle, uniformly distributed over the solid angle it
// subtends (Arvo 1995, "Stratified Sampling of Spherical Triangles"): the
// density of a triangle light seen from a point is then 1/Ω, without the
// d²/cos θ of sampling by area, which is what makes large, near lights noisy.
#pragma once

#include "core/vec3.h"
#include "core/vec3d.h"

namespace sombra {

// The triangle (p0, p1, p2) as seen from x: the unit directions toward its
// corners and its solid angle Ω in steradians. Computed in double: Arvo's
// formulas subtract nearly equal angles for small triangles.
struct SphericalTriangle {
    Vec3d a{}, b{}, c{};     // unit directions from x to p0, p1, p2
    double solid_angle = 0;  // Ω; 0 when degenerate or seen edge-on
    double alpha = 0;        // the spherical triangle's angle at a
};

SphericalTriangle make_spherical_triangle(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2);

// A unit direction from x into the triangle, uniform over its solid angle
// for (u1, u2) uniform in [0, 1)²; t.solid_angle must be > 0.
Vec3 sample_spherical_triangle(const SphericalTriangle& t, float u1, float u2);

}  // namespace sombra
