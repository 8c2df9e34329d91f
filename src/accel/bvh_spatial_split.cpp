// Spatial splits: chopped binning of triangle references (each reference's
// box cut at every bin plane it crosses, the pieces clipped exactly against
// the triangle), a sweep for the cheapest plane within the reference budget,
// and the partition with Stich's reference unsplitting.
#include "accel/bvh_spatial_split.h"

#include <algorithm>
#include <cmath>

namespace sombra::bvh_build {
namespace {

// Edge crossings are computed in float: the crossing's other coordinates
// may be off by a few ulps of the edge's larger endpoint. Padding them by
// 2^-20 (8 ulps) of that keeps a part's box around the exact part.
constexpr float kCrossingPad = 0x1p-20f;

// The bins of one axis over a node's bounds: plane[b] (b = 1 … bins − 1) is
// the lower face of bin b. Binning and partition both locate coordinates
// against these same floats, so they agree on which side a box lies.
struct AxisBins {
    int bins = 0;
    float lo = 0, scale = 0;
    float plane[kSpatialBins + 1] = {};

    AxisBins(const Box& bounds, int axis, int bin_count) : bins(bin_count), lo(bounds.bmin[axis]) {
        const float extent = bounds.bmax[axis] - lo;
        scale = static_cast<float>(bins) / extent;
        const float width = extent / static_cast<float>(bins);
        for (int b = 1; b < bins; ++b) plane[b] = lo + static_cast<float>(b) * width;
    }
    int estimate(float x) const {
        const float f = (x - lo) * scale;
        if (!(f > 0.0f)) return 0;
        return f < static_cast<float>(bins - 1) ? static_cast<int>(f) : bins - 1;
    }
    // The bin holding a box's lower face x: plane[b] ≤ x < plane[b + 1].
    int entry(float x) const {
        int b = estimate(x);
        while (b > 0 && x < plane[b]) --b;
        while (b + 1 < bins && x >= plane[b + 1]) ++b;
        return b;
    }
    // The bin holding a box's upper face x: plane[b] < x ≤ plane[b + 1], but
    // not before the entry bin (a box flat on a plane lies in one bin).
    // So a box straddles plane p (entry < p ≤ exit) exactly when
    // bmin < plane[p] < bmax.
    int exit(float x, int entry_bin) const {
        int b = estimate(x);
        while (b > 0 && x <= plane[b]) --b;
        while (b + 1 < bins && x > plane[b + 1]) ++b;
        return std::max(b, entry_bin);
    }
};

void triangle_corners(const TriangleMesh& mesh, std::uint32_t triangle, Vec3 v[3]) {
    const Index3& tri = mesh.triangles[triangle];
    for (int k = 0; k < 3; ++k) v[k] = mesh.positions[tri[k]];
}

__m128 row(Vec3 p) { return _mm_setr_ps(p.x, p.y, p.z, 0.0f); }

}  // namespace

void clip_triangle_box(const Vec3 v[3], const Box& box, int axis, float plane, Box& left, Box& right) {
    left = Box{};
    right = Box{};
    for (int k = 0; k < 3; ++k) {
        const Vec3 a = v[k], b = v[(k + 1) % 3];
        if (a[axis] <= plane) left.grow(a);
        if (a[axis] >= plane) right.grow(a);
        if (!((a[axis] < plane && plane < b[axis]) || (b[axis] < plane && plane < a[axis]))) continue;
        // The edge crosses the plane strictly between its ends.
        const float t = std::clamp((plane - a[axis]) / (b[axis] - a[axis]), 0.0f, 1.0f);
        Box crossing;
        for (int d = 0; d < 3; ++d) {
            if (d == axis) {
                crossing.bmin[d] = crossing.bmax[d] = plane;
                continue;
            }
            const float c = a[d] + t * (b[d] - a[d]);
            const float pad = std::max(std::fabs(a[d]), std::fabs(b[d])) * kCrossingPad;
            // The exact crossing lies between the edge's ends, whatever the rounding.
            crossing.bmin[d] = std::max(c - pad, std::min(a[d], b[d]));
            crossing.bmax[d] = std::min(c + pad, std::max(a[d], b[d]));
        }
        left.grow(crossing);
        right.grow(crossing);
    }
    left = intersection(left, box);
    right = intersection(right, box);
}

SpatialSplit find_spatial_split(const PrimRef* refs, const RefRange& range, const TriangleMesh& mesh) {
    const std::uint32_t count = range.count();
    const int nbins = count < static_cast<std::uint32_t>(kSpatialBins) ? static_cast<int>(count) : kSpatialBins;
    struct Bin {
        BoxRows bounds;
        std::uint32_t entries = 0, exits = 0;  // references whose lower / upper face lies in the bin
    };
    Bin bins[3][kSpatialBins];
    const AxisBins axes[3] = {{range.bounds, 0, nbins}, {range.bounds, 1, nbins}, {range.bounds, 2, nbins}};
    bool usable[3];
    for (int a = 0; a < 3; ++a) usable[a] = range.bounds.bmax[a] > range.bounds.bmin[a];

    // One pass over the references for all three axes: each is read once,
    // its triangle only when it crosses a plane.
    for (std::uint32_t i = range.begin; i < range.end; ++i) {
        const PrimRef& ref = refs[i];
        bool have_corners = false;
        Vec3 corners[3];
        for (int a = 0; a < 3; ++a) {
            if (!usable[a]) continue;
            const AxisBins& ax = axes[a];
            const int first = ax.entry(ref.bmin[a]);
            const int last = ax.exit(ref.bmax[a], first);
            ++bins[a][first].entries;
            ++bins[a][last].exits;
            if (first == last) {
                bins[a][first].bounds.grow(ref.lo(), ref.hi());
                continue;
            }
            if (!have_corners) {
                triangle_corners(mesh, ref.triangle, corners);
                have_corners = true;
            }
            // Chop: the part left of each plane goes to its bin, the rest on.
            Box rest = ref.box();
            for (int b = first; b < last && !rest.empty(); ++b) {
                Box piece, beyond;
                clip_triangle_box(corners, rest, a, ax.plane[b + 1], piece, beyond);
                if (!piece.empty()) bins[a][b].bounds.grow(row(piece.bmin), row(piece.bmax));
                rest = beyond;
            }
            if (!rest.empty()) bins[a][last].bounds.grow(row(rest.bmin), row(rest.bmax));
        }
    }

    SpatialSplit best;
    const std::uint32_t spare = range.spare();
    for (int a = 0; a < 3; ++a) {
        if (!usable[a]) continue;
        // Sweep from the right: the bounds, reference count and cost of bins [b, nbins).
        float right_cost[kSpatialBins];
        std::uint32_t right_counts[kSpatialBins];
        Box right_boxes[kSpatialBins];
        BoxRows right;
        std::uint32_t right_count = 0;
        for (int b = nbins - 1; b > 0; --b) {
            right.grow(bins[a][b].bounds.lo, bins[a][b].bounds.hi);
            right_count += bins[a][b].exits;
            right_boxes[b] = right.box();
            right_counts[b] = right_count;
            right_cost[b] = right_boxes[b].half_area() * blocks_of(right_count);
        }
        BoxRows left;
        std::uint32_t left_count = 0;
        for (int b = 1; b < nbins; ++b) {
            left.grow(bins[a][b - 1].bounds.lo, bins[a][b - 1].bounds.hi);
            left_count += bins[a][b - 1].entries;
            if (left_count == 0 || right_counts[b] == 0) continue;
            if (left_count + right_counts[b] - count > spare) continue;  // over the reference budget
            const Box left_box = left.box();
            if (left_box.empty() || right_boxes[b].empty()) continue;
            const float cost = left_box.half_area() * blocks_of(left_count) + right_cost[b];
            if (cost < best.cost) best = SpatialSplit{a, b, cost, left_count, right_counts[b], left_box, right_boxes[b]};
        }
    }
    return best;
}

void partition_spatial(const PrimRef* refs, const RefRange& range, const SpatialSplit& split,
                       const TriangleMesh& mesh, std::vector<PrimRef>& left, std::vector<PrimRef>& right) {
    left.clear();
    right.clear();
    const int a = split.axis;
    const std::uint32_t count = range.count();
    const int nbins = count < static_cast<std::uint32_t>(kSpatialBins) ? static_cast<int>(count) : kSpatialBins;
    const AxisBins ax(range.bounds, a, nbins);
    const float plane = ax.plane[split.plane];
    // Stich's unsplitting compares, per straddling reference, the SAH of
    // the planned children (linear in the counts) with the reference
    // clipped into both against whole in one.
    const float left_area = split.left_bounds.half_area(), right_area = split.right_bounds.half_area();
    const auto nl = static_cast<float>(split.left_count), nr = static_cast<float>(split.right_count);
    const float split_cost = left_area * nl + right_area * nr;
    for (std::uint32_t i = range.begin; i < range.end; ++i) {
        const PrimRef& ref = refs[i];
        const int first = ax.entry(ref.bmin[a]);
        const int last = ax.exit(ref.bmax[a], first);
        if (last < split.plane) {
            left.push_back(ref);
            continue;
        }
        if (first >= split.plane) {
            right.push_back(ref);
            continue;
        }
        Box whole_left = split.left_bounds, whole_right = split.right_bounds;
        whole_left.grow(ref.box());
        whole_right.grow(ref.box());
        const float cost_left = whole_left.half_area() * nl + right_area * (nr - 1.0f);
        const float cost_right = left_area * (nl - 1.0f) + whole_right.half_area() * nr;
        if (cost_left <= split_cost && cost_left <= cost_right) {
            left.push_back(ref);
            continue;
        }
        if (cost_right <= split_cost) {
            right.push_back(ref);
            continue;
        }
        Vec3 corners[3];
        triangle_corners(mesh, ref.triangle, corners);
        Box left_part, right_part;
        clip_triangle_box(corners, ref.box(), a, plane, left_part, right_part);
        auto with_box = [&ref](const Box& box) {
            PrimRef part = ref;
            part.bmin = box.bmin;
            part.bmax = box.bmax;
            return part;
        };
        if (left_part.empty() && right_part.empty()) {
            right.push_back(ref);  // cannot happen for a box around part of the triangle; stay safe
        } else if (left_part.empty()) {
            right.push_back(with_box(right_part));
        } else if (right_part.empty()) {
            left.push_back(with_box(left_part));
        } else {
            left.push_back(with_box(left_part));
            right.push_back(with_box(right_part));
        }
    }
}

}  // namespace sombra::bvh_build
