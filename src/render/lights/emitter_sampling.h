// Where on an emitter next-event estimation aims, once sample_light
// (render/lights/lights.h) has chosen it: a point on an emitting triangle, or on a
// rectangle two emitting triangles make (a quad light), uniform over the
// solid angle the shape subtends from the shading point where that pays,
// else uniform over its area. Each sampler reports the solid-angle density
// its pdf_* twin gives for the same point, which MIS relies on.
#pragma once

#include <array>
#include <cstdint>

#include "core/vec3.h"

namespace sombra {

// Two emitting triangles of one material that together make a rectangle
// (a quad light with perpendicular edges, or a mesh's rectangular light):
// sample_light samples them as one light, with the two triangles' choice
// probabilities added, and reports the triangle the point falls in.
struct EmitterRectangle {
    Vec3 corner, edge1, edge2;  // corner + s·edge1 + t·edge2, s, t in [0, 1]; edge1 ⟂ edge2
    Vec3 unit_normal;           // the triangles' winding normal
    Vec3 centre;
    float area = 0;
    float inv_length2_1 = 0, inv_length2_2 = 0;  // 1/|edge1|², 1/|edge2|²: (s, t) of a point
    // The squared distance from the centre beyond which a point is never
    // sampled by solid angle (too far for the rectangle to span a wide
    // range of distances from it).
    float solid_angle_reach2 = 0;
    std::uint32_t near = 0;  // the emitter (index in LightSet::emitters) whose triangle has `corner`: s + t ≤ 1
    std::uint32_t far = 0;   // the other one
};

inline constexpr std::uint32_t kNoRectangle = 0xffffffffu;

// The rectangle that triangles a and b (world corners, winding order) make
// together, when they do: they share two corners (bit for bit, as a quad's
// two triangles or a mesh's shared vertices do), wind the same way, and
// their other two corners complete a rectangle up to float rounding. Its
// corner is a's own corner; near and far are left for the caller.
bool find_rectangle(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, EmitterRectangle& out);

// A point y on triangle p0 p1 p2 (unit winding normal n, area `area`) for
// the shading point x, with its solid-angle density from x and the unit
// direction wi from x to it. False when nothing can be sampled.
bool sample_emitter_triangle(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 n, float area, float u1, float u2, Vec3& y,
                             Vec3& wi, float& pdf);
float pdf_emitter_triangle(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 n, float area, Vec3 y);

// The same for rectangle r; in_near tells whether y lies in r.near's triangle.
bool sample_emitter_rectangle(const EmitterRectangle& r, Vec3 x, float u1, float u2, Vec3& y, Vec3& wi, float& pdf,
                              bool& in_near);
float pdf_emitter_rectangle(const EmitterRectangle& r, Vec3 x, Vec3 y);

}  // namespace sombra
