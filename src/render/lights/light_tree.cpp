#include "render/lights/light_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace sombra {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr int kBins = 12;
// The cone's half-angle is widened by this much (radians) against rounding.
constexpr float kConePad = 1e-4f;

// A bounding cone of directions (θ_o, θ_e = π/2 implied), used while building.
struct Cone {
    Vec3 axis{0, 0, 1};
    float cos_theta = 1;
    bool empty = true;
};

float safe_sqrt(float v) { return std::sqrt(std::max(0.0f, v)); }
float safe_acos(float v) { return std::acos(std::clamp(v, -1.0f, 1.0f)); }

// Rotation of v about the unit axis k by angle a (Rodrigues).
Vec3 rotate(Vec3 v, Vec3 k, float a) {
    const float c = std::cos(a), s = std::sin(a);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

// The smallest cone containing both (pbrt-v4's DirectionCone Union); only
// guides the split heuristic, node cones are computed from their emitters.
Cone cone_union(const Cone& a, const Cone& b) {
    if (a.empty) return b;
    if (b.empty) return a;
    const float theta_a = safe_acos(a.cos_theta), theta_b = safe_acos(b.cos_theta);
    const float theta_d = safe_acos(dot(a.axis, b.axis));
    if (std::min(theta_d + theta_b, kPi) <= theta_a) return a;
    if (std::min(theta_d + theta_a, kPi) <= theta_b) return b;
    const float theta_o = 0.5f * (theta_a + theta_d + theta_b);
    const Vec3 k = cross(a.axis, b.axis);
    if (theta_o >= kPi || !(dot(k, k) > 0.0f)) return Cone{a.axis, -1.0f, false};
    return Cone{normalize(rotate(a.axis, normalize(k), theta_o - theta_a)), std::cos(theta_o), false};
}

// Conty & Kulla's orientation measure M_Ω of a cone with θ_e = π/2.
float orientation_measure(float cos_theta_o) {
    const float theta_o = safe_acos(cos_theta_o);
    const float theta_w = std::min(theta_o + 0.5f * kPi, kPi);
    const float sin_theta_o = safe_sqrt(1 - cos_theta_o * cos_theta_o);
    return 2 * kPi * (1 - cos_theta_o) +
           0.5f * kPi *
               (2 * theta_w * sin_theta_o - std::cos(theta_o - 2 * theta_w) - 2 * theta_o * sin_theta_o + cos_theta_o);
}

struct Record {
    Vec3 bmin, bmax, centroid, normal;
    float power;
    bool two_sided;
    std::uint32_t index;
};

struct Bin {
    Vec3 bmin{std::numeric_limits<float>::max()}, bmax{-std::numeric_limits<float>::max()};
    float power = 0;
    Cone cone;
    bool two_sided = false;
    void add(const Bin& o) {
        bmin = min(bmin, o.bmin);
        bmax = max(bmax, o.bmax);
        power += o.power;
        cone = cone_union(cone, o.cone);
        two_sided = two_sided || o.two_sided;
    }
    float cost(float kr) const {
        const Vec3 d = max(bmax - bmin, Vec3{0.0f});
        const float area = 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
        return power * orientation_measure(cone.cos_theta) * (two_sided ? 2.0f : 1.0f) * kr * area;
    }
};

Bin bin_of(const Record& r) {
    Bin b;
    b.bmin = r.bmin;
    b.bmax = r.bmax;
    b.power = r.power;
    b.cone = Cone{r.normal, 1.0f, false};
    b.two_sided = r.two_sided;
    return b;
}

// The node bounding records [first, last): box and power summed, and the
// cone from the normals themselves (so it holds every one of them).
LightTreeNode bound(const Record* first, const Record* last) {
    LightTreeNode node;
    node.bmin = Vec3{std::numeric_limits<float>::max()};
    node.bmax = Vec3{-std::numeric_limits<float>::max()};
    double power = 0;
    bool two_sided = false;
    Vec3 sum{0.0f};
    for (const Record* r = first; r != last; ++r) {
        node.bmin = min(node.bmin, r->bmin);
        node.bmax = max(node.bmax, r->bmax);
        power += r->power;
        two_sided = two_sided || r->two_sided;
        // Two-sided normals count with either sign: align them with the first.
        sum += r->two_sided && dot(r->normal, first->normal) < 0.0f ? -r->normal : r->normal;
    }
    node.power = static_cast<float>(power);
    node.axis = dot(sum, sum) > 0.0f ? normalize(sum) : first->normal;
    float cos_min = 1.0f;
    for (const Record* r = first; r != last; ++r) {
        const float c = dot(node.axis, r->normal);
        cos_min = std::min(cos_min, two_sided ? std::fabs(c) : c);
    }
    node.cos_theta_o = std::cos(std::min(safe_acos(cos_min) + kConePad, kPi));
    if (two_sided) node.payload |= LightTreeNode::kTwoSided;
    return node;
}

// Splits [first, last) (at least two records) and returns the middle.
Record* split(Record* first, Record* last, const LightTreeNode& node, bool median) {
    const auto count = last - first;
    if (!median) {
        Vec3 cmin{std::numeric_limits<float>::max()}, cmax{-std::numeric_limits<float>::max()};
        for (const Record* r = first; r != last; ++r) {
            cmin = min(cmin, r->centroid);
            cmax = max(cmax, r->centroid);
        }
        const Vec3 diag = node.bmax - node.bmin;
        float best_cost = std::numeric_limits<float>::infinity();
        int best_axis = -1, best_bin = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const float extent = cmax[axis] - cmin[axis];
            if (!(extent > 0.0f)) continue;
            std::array<Bin, kBins> bins;
            for (const Record* r = first; r != last; ++r) {
                const int b =
                    std::min(kBins - 1, static_cast<int>(kBins * ((r->centroid[axis] - cmin[axis]) / extent)));
                bins[static_cast<std::size_t>(b)].add(bin_of(*r));
            }
            // Kr favours cuts across the box's long side.
            const float kr = max_component(diag) / std::max(diag[axis], 1e-20f);
            std::array<float, kBins> below{};
            Bin acc;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.add(bins[static_cast<std::size_t>(b)]);
                below[static_cast<std::size_t>(b)] = acc.power > 0.0f ? acc.cost(kr) : 0.0f;
            }
            acc = Bin{};
            for (int b = kBins - 1; b > 0; --b) {
                acc.add(bins[static_cast<std::size_t>(b)]);
                const float cost = below[static_cast<std::size_t>(b - 1)] + (acc.power > 0.0f ? acc.cost(kr) : 0.0f);
                if (cost < best_cost) {
                    best_cost = cost;
                    best_axis = axis;
                    best_bin = b;
                }
            }
        }
        if (best_axis >= 0) {
            const float extent = cmax[best_axis] - cmin[best_axis];
            Record* mid = std::partition(first, last, [&](const Record& r) {
                return std::min(kBins - 1,
                                static_cast<int>(kBins * ((r.centroid[best_axis] - cmin[best_axis]) / extent))) <
                       best_bin;
            });
            if (mid != first && mid != last) return mid;
        }
    }
    // Median along the box's longest axis.
    const Vec3 diag = node.bmax - node.bmin;
    const int axis = diag.x >= diag.y && diag.x >= diag.z ? 0 : (diag.y >= diag.z ? 1 : 2);
    Record* mid = first + count / 2;
    std::nth_element(first, mid, last,
                     [axis](const Record& a, const Record& b) { return a.centroid[axis] < b.centroid[axis]; });
    return mid;
}

int ceil_log2(std::ptrdiff_t n) {
    int k = 0;
    while ((std::ptrdiff_t{1} << k) < n) ++k;
    return k;
}

void build(LightTree& tree, Record* first, Record* last, int depth, std::uint64_t trail) {
    const auto at = static_cast<std::uint32_t>(tree.nodes.size());
    tree.nodes.push_back(bound(first, last));
    if (last - first == 1) {
        tree.nodes[at].payload |= LightTreeNode::kLeaf | first->index;
        tree.trails[first->index] = trail;
        return;
    }
    // Trails hold 63 steps: split at the median once the depth left is short.
    const bool median = depth + ceil_log2(last - first) >= 62;
    Record* mid = split(first, last, tree.nodes[at], median);
    build(tree, first, mid, depth + 1, trail);
    tree.nodes[at].payload |= static_cast<std::uint32_t>(tree.nodes.size());
    build(tree, mid, last, depth + 1, trail | (std::uint64_t{1} << depth));
}

// cos(max(0, a − b)) from the sines and cosines of a and b.
float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
    if (cos_a > cos_b) return 1.0f;
    return cos_a * cos_b + sin_a * sin_b;
}
float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
    if (cos_a > cos_b) return 0.0f;
    return sin_a * cos_b - cos_a * sin_b;
}

// The probability of the first child of interior node `node` (NaN when both
// children have importance 0). One function for sampling and pmf alike.
[[gnu::noinline]] float first_child_probability(const LightTree& tree, std::uint32_t node, Vec3 x, Vec3 n) {
    const float a = light_tree_importance(tree.nodes[node + 1], x, n);
    const float b = light_tree_importance(tree.nodes[tree.nodes[node].index()], x, n);
    return a / (a + b);
}

}  // namespace

LightTree make_light_tree(const std::vector<LightTreeEmitter>& emitters) {
    LightTree tree;
    if (emitters.empty()) return tree;
    std::vector<Record> records;
    records.reserve(emitters.size());
    for (std::size_t i = 0; i < emitters.size(); ++i) {
        const LightTreeEmitter& e = emitters[i];
        const Vec3 lo = min(e.p0, min(e.p1, e.p2)), hi = max(e.p0, max(e.p1, e.p2));
        records.push_back({lo, hi, 0.5f * (lo + hi), normalize(cross(e.p1 - e.p0, e.p2 - e.p0)), e.power, e.two_sided,
                           static_cast<std::uint32_t>(i)});
    }
    tree.trails.assign(emitters.size(), 0);
    tree.nodes.reserve(2 * emitters.size() - 1);
    build(tree, records.data(), records.data() + records.size(), 0, 0);
    return tree;
}

float light_tree_importance(const LightTreeNode& node, Vec3 x, Vec3 n) {
    const Vec3 centre = 0.5f * (node.bmin + node.bmax);
    const Vec3 diag = node.bmax - node.bmin;
    const Vec3 to_x = x - centre;
    const float dist2 = dot(to_x, to_x);
    const float radius2 = 0.25f * dot(diag, diag);  // the box's bounding sphere
    const float d2 = std::max(dist2, radius2);
    // Inside the bounding sphere every direction is possible: no angular bound.
    if (!(dist2 > radius2)) return node.power / d2;
    const Vec3 wi = to_x / std::sqrt(dist2);  // from the centre towards x
    // θ_b: the half-angle the bounding sphere subtends from x.
    const float sin2_theta_b = radius2 / dist2;
    const float cos_theta_b = safe_sqrt(1 - sin2_theta_b), sin_theta_b = std::sqrt(sin2_theta_b);
    // θ' = max(0, θ_w − θ_o − θ_b): the least angle between an emitter
    // normal and the direction to x; nothing leaves beyond θ_e = π/2.
    float cos_theta_w = dot(node.axis, wi);
    if (node.two_sided()) cos_theta_w = std::fabs(cos_theta_w);
    const float sin_theta_w = safe_sqrt(1 - cos_theta_w * cos_theta_w);
    const float sin_theta_o = safe_sqrt(1 - node.cos_theta_o * node.cos_theta_o);
    const float cos_x = cos_sub_clamped(sin_theta_w, cos_theta_w, sin_theta_o, node.cos_theta_o);
    const float sin_x = sin_sub_clamped(sin_theta_w, cos_theta_w, sin_theta_o, node.cos_theta_o);
    const float cos_theta_p = cos_sub_clamped(sin_x, cos_x, sin_theta_b, cos_theta_b);
    if (!(cos_theta_p > 0.0f)) return 0.0f;
    float importance = node.power * cos_theta_p / d2;
    if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) {
        // |cos| at x (reflection or transmission), bounded over the box.
        const float cos_i = std::fabs(dot(wi, n));
        const float sin_i = safe_sqrt(1 - cos_i * cos_i);
        importance *= cos_sub_clamped(sin_i, cos_i, sin_theta_b, cos_theta_b);
    }
    return std::max(importance, 0.0f);
}

LightTreeChoice sample_light_tree(const LightTree& tree, Vec3 x, Vec3 n, float u) {
    if (tree.nodes.empty()) return {};
    if (!(light_tree_importance(tree.nodes[0], x, n) > 0.0f)) return {};
    std::uint32_t node = 0;
    float probability = 1.0f;
    while (!tree.nodes[node].leaf()) {
        const float p = first_child_probability(tree, node, x, n);
        if (!(p >= 0.0f)) return {};  // both children 0
        if (u < p) {
            u = std::min(u / p, 0x1.fffffep-1f);
            probability = probability * p;
            node = node + 1;
        } else {
            u = std::min((u - p) / (1.0f - p), 0x1.fffffep-1f);
            probability = probability * (1.0f - p);
            node = tree.nodes[node].index();
        }
    }
    if (!(probability > 0.0f)) return {};
    return {tree.nodes[node].index(), probability};
}

float pmf_light_tree(const LightTree& tree, Vec3 x, Vec3 n, std::uint32_t emitter) {
    if (emitter >= tree.trails.size()) return 0.0f;
    if (!(light_tree_importance(tree.nodes[0], x, n) > 0.0f)) return 0.0f;
    const std::uint64_t trail = tree.trails[emitter];
    std::uint32_t node = 0;
    float probability = 1.0f;
    for (int depth = 0; !tree.nodes[node].leaf(); ++depth) {
        const float p = first_child_probability(tree, node, x, n);
        if (!(p >= 0.0f)) return 0.0f;
        if (((trail >> depth) & 1u) == 0) {
            probability = probability * p;
            node = node + 1;
        } else {
            probability = probability * (1.0f - p);
            node = tree.nodes[node].index();
        }
    }
    return probability;
}

}  // namespace sombra
