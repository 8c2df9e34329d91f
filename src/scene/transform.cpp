// Affine transforms (spec §8). Products and inverses are computed in double and
// rounded once, so long chains of steps do not accumulate float error.
#include "scene/transform.h"

#include <cmath>

namespace sombra {
namespace {

using Mat3d = std::array<std::array<double, 3>, 3>;

Mat3d linear_part(const Transform& t) {
    Mat3d a{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) a[r][c] = t.m[r * 4 + c];
    return a;
}

Transform from_linear(const Mat3d& a) {
    Transform t;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) t.m[r * 4 + c] = static_cast<float>(a[r][c]);
    return t;
}

// cof[r][c] = (-1)^(r+c) · minor(r, c); cof = det · inverse-transpose.
Mat3d cofactors(const Mat3d& a) {
    Mat3d cof{};
    for (int r = 0; r < 3; ++r) {
        const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
        for (int c = 0; c < 3; ++c) {
            const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            // Cyclic index order makes the sign come out right without (-1)^(r+c).
            cof[r][c] = a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1];
        }
    }
    return cof;
}

double det3(const Mat3d& a) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

// Exact sine and cosine at multiples of 90°, so "degrees": 90 maps axes onto axes exactly.
void sin_cos_degrees(double degrees, double& s, double& c) {
    const double reduced = std::fmod(degrees, 360.0);
    const double quarter = reduced / 90.0;
    if (quarter == std::floor(quarter)) {
        static constexpr double kSin[4] = {0, 1, 0, -1};
        static constexpr double kCos[4] = {1, 0, -1, 0};
        const int q = (static_cast<int>(quarter) % 4 + 4) % 4;
        s = kSin[q];
        c = kCos[q];
        return;
    }
    const double radians = reduced * (3.14159265358979323846 / 180.0);
    s = std::sin(radians);
    c = std::cos(radians);
}

}  // namespace

Transform make_scale(Vec3 s) {
    Transform t;
    t.m[0] = s.x;
    t.m[5] = s.y;
    t.m[10] = s.z;
    return t;
}

Transform make_translate(Vec3 v) {
    Transform t;
    t.m[3] = v.x;
    t.m[7] = v.y;
    t.m[11] = v.z;
    return t;
}

Transform make_rotate(Vec3 axis, float degrees) {
    const double ax = axis.x, ay = axis.y, az = axis.z;
    const double len = std::sqrt(ax * ax + ay * ay + az * az);
    if (!(len > 0) || !std::isfinite(len)) return Transform{};  // no direction: nothing to rotate about
    const double x = ax / len, y = ay / len, z = az / len;
    double s = 0, c = 1;
    sin_cos_degrees(degrees, s, c);
    const double k = 1 - c;
    // Rodrigues: R = c·I + s·[a]× + (1 − c)·a·aᵀ, counter-clockwise looking down the axis.
    const Mat3d r{{{c + k * x * x, k * x * y - s * z, k * x * z + s * y},
                   {k * y * x + s * z, c + k * y * y, k * y * z - s * x},
                   {k * z * x - s * y, k * z * y + s * x, c + k * z * z}}};
    return from_linear(r);
}

Transform compose(const Transform& first, const Transform& then) {
    // then · first, with both last rows [0 0 0 1].
    Transform out;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) {
            double sum = c == 3 ? static_cast<double>(then.m[r * 4 + 3]) : 0.0;
            for (int k = 0; k < 3; ++k)
                sum += static_cast<double>(then.m[r * 4 + k]) * static_cast<double>(first.m[k * 4 + c]);
            out.m[r * 4 + c] = static_cast<float>(sum);
        }
    }
    return out;
}

Vec3 transform_point(const Transform& t, Vec3 p) {
    const auto& m = t.m;
    return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
            m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
}

Vec3 transform_vector(const Transform& t, Vec3 v) {
    const auto& m = t.m;
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
            m[8] * v.x + m[9] * v.y + m[10] * v.z};
}

Transform normal_transform(const Transform& t) {
    const Mat3d a = linear_part(t);
    Mat3d cof = cofactors(a);
    const double det = det3(a);
    // A singular t keeps the cofactors: they still carry the normals of what
    // survives (a plane flattened to zero thickness keeps its normal).
    if (det != 0)
        for (auto& row : cof)
            for (double& v : row) v /= det;
    return from_linear(cof);
}

Transform inverse_affine(const Transform& t) {
    const Mat3d a = linear_part(t);
    const Mat3d cof = cofactors(a);
    const double det = det3(a);
    // inverse = cofactorsᵀ / det; the translation is −inverse · t.
    Mat3d inv{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) inv[r][c] = cof[c][r] / det;
    Transform out = from_linear(inv);
    for (int r = 0; r < 3; ++r) {
        double sum = 0;
        for (int k = 0; k < 3; ++k) sum -= inv[r][k] * static_cast<double>(t.m[k * 4 + 3]);
        out.m[r * 4 + 3] = static_cast<float>(sum);
    }
    return out;
}

float determinant3(const Transform& t) { return static_cast<float>(det3(linear_part(t))); }

}  // namespace sombra
