#include "scene/gltf_animation.h"

#include <algorithm>
#include <cmath>

namespace sombra {
namespace {

// T · R · S of a unit (or normalisable) quaternion, in float at the end.
Transform trs(const double t[3], const double q_in[4], const double s[3]) {
    double q[4] = {q_in[0], q_in[1], q_in[2], q_in[3]};
    const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    // A cubic spline may pass through zero: no rotation is the only choice.
    if (!(len > 1e-12))
        q[0] = q[1] = q[2] = 0, q[3] = 1;
    else
        for (double& v : q) v /= len;
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    Transform out;
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) out.m[row * 4 + col] = static_cast<float>(r[row][col] * s[col]);
        out.m[row * 4 + 3] = static_cast<float>(t[row]);
    }
    return out;
}

void normalise4(double* q) {
    const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (len > 1e-12)
        for (int k = 0; k < 4; ++k) q[k] /= len;
}

}  // namespace

void sample_gltf(const GltfSampler& sampler, bool rotation, double time, double* out) {
    const auto& times = sampler.times;
    const std::size_t n = sampler.components;
    const bool cubic = sampler.interpolation == GltfSampler::Interpolation::CubicSpline;
    // Key k's value: the middle of its triple for CUBICSPLINE.
    const auto value = [&](std::size_t k, std::size_t c) {
        return double(sampler.values[(cubic ? 3 * k + 1 : k) * n + c]);
    };
    std::size_t k = 0;
    double u = 0;
    if (time >= times.back()) {
        k = times.size() - 1;
    } else if (time > times.front()) {
        k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), time) - times.begin()) - 1;
        u = (time - times[k]) / (double(times[k + 1]) - times[k]);
    }
    if (u == 0 || sampler.interpolation == GltfSampler::Interpolation::Step) {
        for (std::size_t c = 0; c < n; ++c) out[c] = value(k, c);
    } else if (!cubic) {
        double a[4], b[4];
        for (std::size_t c = 0; c < n; ++c) a[c] = value(k, c), b[c] = value(k + 1, c);
        if (!rotation) {
            for (std::size_t c = 0; c < n; ++c) out[c] = a[c] + (b[c] - a[c]) * u;
        } else {
            // Slerp along the shorter arc (glTF 2.0 Appendix C), of unit keys
            // (normalised integers are only nearly so).
            normalise4(a);
            normalise4(b);
            double dot = 0;
            for (std::size_t c = 0; c < 4; ++c) dot += a[c] * b[c];
            if (dot < 0)
                for (double& v : b) v = -v;
            const double cosine = std::min(std::fabs(dot), 1.0);
            double wa = 1 - u, wb = u;
            if (cosine < 0.9995) {
                const double theta = std::acos(cosine), s = std::sin(theta);
                wa = std::sin((1 - u) * theta) / s;
                wb = std::sin(u * theta) / s;
            }
            for (std::size_t c = 0; c < 4; ++c) out[c] = wa * a[c] + wb * b[c];
        }
    } else {
        // Hermite spline; tangents scaled by the key interval (glTF 2.0 Appendix C).
        const double td = double(times[k + 1]) - times[k];
        const double u2 = u * u, u3 = u2 * u;
        const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
        for (std::size_t c = 0; c < n; ++c) {
            const double out_tangent = sampler.values[(3 * k + 2) * n + c];
            const double in_tangent = sampler.values[(3 * (k + 1)) * n + c];
            out[c] = h00 * value(k, c) + h10 * td * out_tangent + h01 * value(k + 1, c) + h11 * td * in_tangent;
        }
    }
    if (rotation) normalise4(out);
}

std::vector<Transform> gltf_node_worlds(const GltfNodeAnimation& animation, double time) {
    struct Local {
        double t[3], r[4], s[3];
    };
    std::vector<Local> locals(animation.nodes.size());
    for (std::size_t i = 0; i < animation.nodes.size(); ++i) {
        const GltfNodeAnimation::Node& n = animation.nodes[i];
        std::copy(n.translation, n.translation + 3, locals[i].t);
        std::copy(n.rotation, n.rotation + 4, locals[i].r);
        std::copy(n.scale, n.scale + 3, locals[i].s);
    }
    for (const GltfChannel& c : animation.channels) {
        Local& l = locals[c.node];
        const GltfSampler& s = animation.samplers[c.sampler];
        switch (c.path) {
            case GltfChannel::Path::Translation: sample_gltf(s, false, time, l.t); break;
            case GltfChannel::Path::Rotation: sample_gltf(s, true, time, l.r); break;
            case GltfChannel::Path::Scale: sample_gltf(s, false, time, l.s); break;
        }
    }
    std::vector<Transform> world(animation.nodes.size());
    for (const std::uint32_t i : animation.order) {
        const GltfNodeAnimation::Node& n = animation.nodes[i];
        const Transform local = n.has_matrix ? n.matrix : trs(locals[i].t, locals[i].r, locals[i].s);
        // compose(a, b): a first, then b; the parent is placed before `order` reaches the child.
        world[i] = n.parent < 0 ? local : compose(local, world[std::size_t(n.parent)]);
    }
    return world;
}

bool gltf_camera_frame(const Transform& world, Vec3& origin, Vec3& forward, Vec3& up) {
    origin = transform_point(world, Vec3{0.0f});
    forward = normalize(transform_vector(world, Vec3{0, 0, -1}));
    const Vec3 node_up = transform_vector(world, Vec3{0, 1, 0});
    up = normalize(node_up - dot(node_up, forward) * forward);
    // A zero vector's normalisation is not finite.
    return is_finite(origin) && is_finite(forward) && is_finite(up);
}

}  // namespace sombra
