// Polygon splitting (spec §9): fans where a fan is right, ear clipping where
// it would overlap, always n - 2 triangles.
#include "io/mesh_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "io/mesh_file.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using testing::TempFolder;
using testing::twice_area_along;

std::vector<PolygonTriangle> split(const std::vector<Vec3>& corners, PolygonSplit* kind = nullptr) {
    PolygonScratch scratch;
    std::vector<PolygonTriangle> out;
    const PolygonSplit how = triangulate_polygon(corners, scratch, out);
    if (kind) *kind = how;
    return out;
}

// Twice the polygon's area along `normal` (shoelace / Newell).
float twice_polygon_area(const std::vector<Vec3>& corners, Vec3 normal) {
    Vec3 sum{0, 0, 0};
    for (std::size_t i = 0; i < corners.size(); ++i) sum += cross(corners[i], corners[(i + 1) % corners.size()]);
    return dot(sum, normal);
}

// Places 2D points on a tilted plane, so the split cannot rely on an axis.
std::vector<Vec3> on_tilted_plane(const std::vector<std::pair<float, float>>& points, Vec3* normal) {
    const Vec3 u = normalize(Vec3(1, 1, 0));
    const Vec3 v = normalize(Vec3(-1, 1, 2));
    *normal = cross(u, v);
    std::vector<Vec3> out;
    for (const auto& [a, b] : points) out.push_back(Vec3(10, -3, 7) + a * u + b * v);
    return out;
}

TEST(PolygonSplit, QuadAndConvexPentagonAreFans) {
    PolygonSplit kind{};
    EXPECT_EQ(split({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, &kind),
              (std::vector<PolygonTriangle>{{0, 1, 2}, {0, 2, 3}}));
    EXPECT_EQ(kind, PolygonSplit::Fan);
    EXPECT_EQ(split({{0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {1, 2, 0}, {-1, 1, 0}}, &kind),
              (std::vector<PolygonTriangle>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
    EXPECT_EQ(kind, PolygonSplit::Fan);
}

TEST(PolygonSplit, ConcaveQuadIsStillAFan) {
    // A dart: the fan from corner 0 overlaps, but spec §9 keeps quads as fans.
    EXPECT_EQ(split({{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {1, 1, 0}}),
              (std::vector<PolygonTriangle>{{0, 1, 2}, {0, 2, 3}}));
}

TEST(PolygonSplit, StarShapedFromCornerZeroStaysAFan) {
    // An L whose first corner sees every other corner.
    PolygonSplit kind{};
    split({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, &kind);
    EXPECT_EQ(kind, PolygonSplit::Fan);
}

TEST(PolygonSplit, ConcavePolygonIsEarClippedWithoutOverlap) {
    // The same L starting at (2, 0): the fan's triangle (2,0)-(1,2)-(0,2)
    // would cover the missing corner square.
    Vec3 normal;
    const std::vector<Vec3> corners = on_tilted_plane({{2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}}, &normal);
    PolygonSplit kind{};
    const std::vector<PolygonTriangle> tris = split(corners, &kind);
    EXPECT_EQ(kind, PolygonSplit::EarClipped);
    ASSERT_EQ(tris.size(), corners.size() - 2);
    float total = 0;
    for (const PolygonTriangle& t : tris) {
        const float area = twice_area_along(corners[t[0]], corners[t[1]], corners[t[2]], normal);
        EXPECT_GT(area, 0) << "every triangle turns like the polygon";
        total += std::fabs(area);
    }
    EXPECT_NEAR(total, twice_polygon_area(corners, normal), 1e-4f);
    EXPECT_NEAR(total, 2 * 3.0f, 1e-4f);
}

TEST(PolygonSplit, CombIsEarClippedWithoutOverlap) {
    // A comb with 8 teeth (34 corners), clockwise, starting inside a notch.
    std::vector<std::pair<float, float>> outline;
    for (int tooth = 0; tooth < 8; ++tooth) {
        const float x = float(tooth);
        outline.insert(outline.end(), {{x + 0.25f, 1}, {x + 0.25f, 3}, {x + 0.75f, 3}, {x + 0.75f, 1}});
    }
    outline.insert(outline.end(), {{8, 1}, {8, 0}});
    outline.insert(outline.end(), {{0, 0}, {0, 1}});
    Vec3 normal;
    const std::vector<Vec3> corners = on_tilted_plane(outline, &normal);
    const std::vector<PolygonTriangle> tris = split(corners);
    ASSERT_EQ(tris.size(), corners.size() - 2);
    const float polygon = twice_polygon_area(corners, normal);  // negative: clockwise
    float total = 0;
    for (const PolygonTriangle& t : tris) {
        const float area = twice_area_along(corners[t[0]], corners[t[1]], corners[t[2]], normal);
        EXPECT_LT(area, 1e-5f) << "every triangle turns like the polygon";
        total += std::fabs(area);
    }
    EXPECT_NEAR(total, std::fabs(polygon), 1e-3f);
    EXPECT_NEAR(total, 2 * (8 + 8 * 0.5f * 2), 1e-3f);
}

TEST(PolygonSplit, DegenerateAndNonFinitePolygonsStillGiveNMinus2) {
    // Collinear corners, all corners equal, a NaN corner.
    EXPECT_EQ(split({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}, {5, 0, 0}}).size(), 4u);
    EXPECT_EQ(split(std::vector<Vec3>(7, Vec3(1, 2, 3))).size(), 5u);
    EXPECT_EQ(
        split({{0, 0, 0}, {1, 0, 0}, {std::numeric_limits<float>::quiet_NaN(), 1, 0}, {1, 1, 0}, {0, 1, 0}}).size(),
        3u);
    EXPECT_TRUE(split({{0, 0, 0}, {1, 0, 0}}).empty());
}

TEST(PolygonSplit, SelfOverlappingOutlineGivesNMinus2) {
    // A pentagram: no proper ear exists everywhere, the count must hold.
    std::vector<Vec3> star;
    for (int i = 0; i < 5; ++i) {
        const double a = 2 * std::numbers::pi * (2 * i) / 5;
        star.push_back({float(std::cos(a)), float(std::sin(a)), 0});
    }
    EXPECT_EQ(split(star).size(), 3u);
}

TEST(PolygonSplit, ObjFacesKeepFanOrderAndClipConcaveOnes) {
    TempFolder tmp;
    Diagnostics diag;
    const TriangleMesh mesh =
        load_obj(tmp.write("p.obj",
                           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\n"
                           "v 2 0 5\nv 2 1 5\nv 1 1 5\nv 1 2 5\nv 0 2 5\nv 0 0 5\n"
                           "f 1 2 3 4\nf 1 5 6 7 8\nf 9 10 11 12 13 14\n"),
                 diag)
            .mesh;
    ASSERT_EQ(mesh.triangle_count(), 2u + 3u + 4u);
    EXPECT_EQ(mesh.triangles[0], (Index3{0, 1, 2}));
    EXPECT_EQ(mesh.triangles[1], (Index3{0, 2, 3}));
    EXPECT_EQ(mesh.triangles[2], (Index3{0, 4, 5}));
    EXPECT_EQ(mesh.triangles[3], (Index3{0, 5, 6}));
    EXPECT_EQ(mesh.triangles[4], (Index3{0, 6, 7}));
    float total = 0;
    for (std::size_t t = 5; t < 9; ++t) {
        const Index3& c = mesh.triangles[t];
        const float area =
            twice_area_along(mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]], {0, 0, 1});
        EXPECT_GT(area, 0);
        total += area;
    }
    EXPECT_NEAR(total, 6.0f, 1e-5f);
}

}  // namespace
}  // namespace sombra
