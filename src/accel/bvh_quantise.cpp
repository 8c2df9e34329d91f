// Quantising a wide node's child boxes to 8-bit grid indices (bvh.h). Each
// axis gets 256 planes, plane_value(origin, scale, q) for q = 0 … 255, from
// the node's box's min corner to at least its max corner; a child's min
// goes to the highest plane at or below it and its max to the lowest plane
// at or above it, each checked with the very float operations the traversal
// performs, so the quantised box contains the child's box whatever the
// rounding.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "accel/bvh.h"
#include "accel/bvh_quantise.h"

namespace sombra {
namespace {

// About the smallest step whose last plane, computed as traversal computes
// it, lies at or beyond `hi` (within a few parts in a million: where the
// sum lo + 255 · step rounds down, the step grows by doubling increments).
float grid_step(float lo, float hi) {
    float step = static_cast<float>((static_cast<double>(hi) - lo) / 255.0);
    float growth = step * 0x1p-20f;
    while (plane_value(lo, step, 255) < hi) {
        step = std::max(std::nextafter(step, std::numeric_limits<float>::infinity()), step + growth);
        growth = std::max(growth * 2.0f, std::numeric_limits<float>::denorm_min());
    }
    return step;
}

// A first guess at the plane index of `value`, rounded down or up, clamped
// to the grid; the searches below correct it.
std::uint8_t guess_index(float value, float origin, float step, bool round_up) {
    if (!(step > 0.0f)) return 0;
    const double q = (static_cast<double>(value) - origin) / step;
    const double rounded = round_up ? std::ceil(q) : std::floor(q);
    return static_cast<std::uint8_t>(rounded < 0.0 ? 0.0 : (rounded > 255.0 ? 255.0 : rounded));
}

// The highest plane at or below `lo`; plane 0 is the origin, at or below
// every child's min.
std::uint8_t index_below(float lo, float origin, float step) {
    unsigned q = guess_index(lo, origin, step, false);
    while (q > 0 && plane_value(origin, step, static_cast<std::uint8_t>(q)) > lo) --q;
    while (q < 255 && plane_value(origin, step, static_cast<std::uint8_t>(q + 1)) <= lo) ++q;
    return static_cast<std::uint8_t>(q);
}

// The lowest plane at or above `hi`; plane 255 is at or above every child's max.
std::uint8_t index_above(float hi, float origin, float step) {
    unsigned q = guess_index(hi, origin, step, true);
    while (q < 255 && plane_value(origin, step, static_cast<std::uint8_t>(q)) < hi) ++q;
    while (q > 0 && plane_value(origin, step, static_cast<std::uint8_t>(q - 1)) >= hi) --q;
    return static_cast<std::uint8_t>(q);
}

}  // namespace

void quantise_children(const BvhChildBox* children, int size, BvhWideNode& node) {
    constexpr int W = kBvhWidth;
    Vec3 lo = children[0].lo, hi = children[0].hi;
    for (int i = 1; i < size; ++i) {
        lo = min(lo, children[i].lo);
        hi = max(hi, children[i].hi);
    }
    node.used = 0;
    for (int a = 0; a < 3; ++a) {
        node.origin[a] = lo[a];
        node.scale[a] = grid_step(lo[a], hi[a]);
        for (int i = 0; i < W; ++i) {
            node.bounds[(2 * a) * W + i] = i < size ? index_below(children[i].lo[a], node.origin[a], node.scale[a]) : 0;
            node.bounds[(2 * a + 1) * W + i] = i < size ? index_above(children[i].hi[a], node.origin[a], node.scale[a]) : 0;
        }
    }
    for (int i = 0; i < size; ++i) node.used |= static_cast<std::uint8_t>(1u << i);
}

}  // namespace sombra
