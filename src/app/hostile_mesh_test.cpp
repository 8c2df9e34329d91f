// Hostile mesh files through the real executable, one test per row of
// docs/robustness.md's "Hostile inputs" table: PLY counts that lie, OBJ face
// indices out of range, non-finite and degenerate geometry, meshes without
// faces, a missing MTL file. Each ends in one "sombra: error:" line and exit
// 1, or in warnings and a correct image, within seconds and bounded memory.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <vector>

#include "hostile_test_fixture.h"

namespace {

using namespace sombra::cli_test;

class HostileMeshes : public HostileFixture {};

TEST_F(HostileMeshes, PlyHeaderClaimingBillionsOfElements) {
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    write_text(dir_ / "a.ply",
               "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" + xyz + "end_header\nabc");
    expect_error_at(run("render a.ply -o out.png", kSmallMemoryKib), "a.ply",
                    "element 'vertex' claims 4000000000 entries of at least 12 bytes, but only 3 bytes are left");
    write_text(dir_ / "b.ply", "ply\nformat ascii 1.0\nelement vertex 3000000000\n" + xyz + "end_header\n0 0 0\n");
    expect_error_at(run("render b.ply -o out.png", kSmallMemoryKib), "b.ply:8",
                    "element 'vertex' claims 3000000000 entries");
    // Once aborted the process: the face count reached vector::reserve before any check.
    write_text(dir_ / "c.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + xyz +
                                   "element face 18446744073709551615\nproperty list uchar int vertex_indices\n"
                                   "end_header\n" +
                                   std::string(36, '\0'));
    expect_error_at(run("render c.ply -o out.png", kSmallMemoryKib), "c.ply",
                    "element 'face' claims 18446744073709551615 entries");
    write_text(dir_ / "d.ply",
               "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\n" + xyz + "end_header\n");
    expect_error_at(run("render d.ply -o out.png"), "d.ply:3", "is not a non-negative integer");
}

TEST_F(HostileMeshes, ObjFaceIndexZero) {
    write_text(dir_ / "z.obj", kSquareVertices + "f 1 2 3\nf 0 1 2\n");
    expect_error_at(run("render z.obj -o out.png"), "z.obj:6", "face index 0 is not allowed (OBJ indices start at 1)");
    write_text(dir_ / "n.obj", kSquareVertices + "vn 0 0 1\nf 1//1 2//0 3//1\n");
    expect_error_at(run("render n.obj -o out.png"), "n.obj:6", "normal index 0 is not allowed");
}

TEST_F(HostileMeshes, ObjFaceIndexOutOfRange) {
    write_text(dir_ / "a.obj", kSquareVertices + "f 1 2 5\n");
    expect_error_at(run("render a.obj -o out.png"), "a.obj:5", "face index 5 out of range (the file has 4 vertices)");
    // tinyobjloader's atoi wraps these to 2 and -1, both valid: read as given they are far out of range.
    write_text(dir_ / "b.obj", kSquareVertices + "f 1 4294967298 3\n");
    expect_error_at(run("render b.obj -o out.png"), "b.obj:5",
                    "face index 4294967298 out of range (the file has 4 vertices)");
    write_text(dir_ / "c.obj", kSquareVertices + "f 1 2 99999999999999999999\n");
    expect_error_at(run("render c.obj -o out.png"), "c.obj:5", "face index 99999999999999999999 out of range");
    write_text(dir_ / "d.obj", kSquareVertices + "f 1 2 " + std::string(100000, '7') + "\n");
    const RunResult r = run("render d.obj -o out.png");
    expect_error_at(r, "d.obj:5", "face index 777777777777777777777777... out of range");
    EXPECT_LT(r.err.size(), 200u) << "the message quotes the whole number";
}

TEST_F(HostileMeshes, ObjNegativeFaceIndexPastTheStart) {
    write_text(dir_ / "a.obj", kSquareVertices + "f -1 -2 -5\n");
    expect_error_at(run("render a.obj -o out.png"), "a.obj:5",
                    "face index -5 out of range (counting back from the 4 vertices before it)");
    // Relative to the vertices read so far, not to the file's total.
    write_text(dir_ / "b.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
    expect_error_at(run("render b.obj -o out.png"), "b.obj:3",
                    "face index -3 out of range (counting back from the 2 vertices before it)");
    write_text(dir_ / "c.obj", kSquareVertices + "f -4 -3 -2 -1\n");  // the square, relatively
    EXPECT_EQ(run("render c.obj -o out.png --quiet").status, 0);
}

TEST_F(HostileMeshes, NanOrInfCoordinates) {
    const Pfm square = reference();
    write_text(dir_ / "bad.obj", kSquareVertices +
                                     "v nan 0 0\nv 0 inf 0\nv 1e39 0 0\nv 0 0 -1.#IND\n"
                                     "f 1 2 3 4\nf 1 2 5\nf 2 3 6\nf 3 4 7\nf 1 3 8\n");
    RunResult r;
    const Pfm image = render_scene(mesh_scene("bad.obj"), &r);
    expect_warning(r, "bad.obj", "dropped 4 triangles touching 4 vertices with non-finite (nan/inf) coordinates");
    EXPECT_EQ(image.rgb, square.rgb);

    // The same in a binary PLY: a NaN float.
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
        "property float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n";
    const float vertices[15] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, std::nanf(""), 0, 0};
    ply.append(reinterpret_cast<const char*>(vertices), sizeof vertices);
    for (const std::vector<int>& face : std::vector<std::vector<int>>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}}) {
        ply += char(3);
        ply.append(reinterpret_cast<const char*>(face.data()), 12);
    }
    write_text(dir_ / "bad.ply", ply);
    EXPECT_EQ(render_scene(mesh_scene("bad.ply"), &r).rgb, square.rgb);
    expect_warning(r, "bad.ply", "dropped 1 triangle touching 1 vertex with non-finite");

    write_text(dir_ / "all.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_error_at(run("render all.obj -o out.png"), "all.obj",
                    "no triangles left: every triangle touches a non-finite vertex");
    // JSON has no NaN; an overflowing number is a syntax error at its position.
    write_text(dir_ / "s.json", scene(R"({"width": 32, "height": 1e999})"));
    expect_error_at(run("render s.json -o out.png"), "s.json:1:36", "number overflow parsing '1e999'");
}

TEST_F(HostileMeshes, DegenerateAndZeroAreaTriangles) {
    const Pfm square = reference();
    // Repeated corners, three collinear corners on the square's diagonal, and all corners on one point.
    write_text(dir_ / "degenerate.obj", kSquareVertices + "v 0 0 0\nf 1 2 3 4\nf 1 1 2\nf 3 3 3\nf 1 5 3\nf 5 5 5\n");
    for (const char* accel : {"bvh", "brute"}) {
        RunResult r;
        const Pfm image =
            render_scene(mesh_scene("degenerate.obj"), &r, std::string("--stats-json stats.json --accel ") + accel);
        EXPECT_EQ(image.rgb, square.rgb) << accel;
        const auto stats = nlohmann::json::parse(read_text(dir_ / "stats.json"));
        EXPECT_EQ(stats["triangles"], 6) << accel;  // counted, never hit
        EXPECT_EQ(stats["nonfinite_samples"], 0) << accel;
    }
}

TEST_F(HostileMeshes, MeshWithNoFaces) {
    write_text(dir_ / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n");
    expect_error_at(run("render points.obj -o out.png"), "points.obj",
                    "no triangles (3 vertices, no face with 3 or more corners)");
    write_text(dir_ / "empty.obj", "");
    expect_error_at(run("render empty.obj -o out.png"), "empty.obj", "no triangles (0 vertices");
    write_text(dir_ / "nofaces.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nelement face 0\nproperty list uchar int vertex_indices\n"
               "end_header\n0 0 0\n1 0 0\n0 1 0\n");
    expect_error_at(run("render nofaces.ply -o out.png"), "nofaces.ply", "no triangles (3 vertices");
    write_text(dir_ / "s.json", mesh_scene("points.obj"));
    expect_error_at(run("render s.json -o out.png"), "points.obj", "no triangles");
}

TEST_F(HostileMeshes, MissingMtlFile) {
    write_text(dir_ / "plain.obj", kSquareVertices + "f 1 2 3 4\n");
    write_text(dir_ / "mtl.obj", "mtllib nothere.mtl\n" + kSquareVertices + "usemtl red\nf 1 2 3 4\n");
    const std::string camera = R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})";
    // No "material" override: the faces take the OBJ's own, here the default.
    auto without_override = [&](const std::string& mesh) {
        std::string text = scene(R"({"width": 32, "height": 24})", camera, "", mesh);
        text.erase(text.find(R"(, "material": "grey")"), std::strlen(R"(, "material": "grey")"));
        return text;
    };
    const Pfm plain = render_scene(without_override("plain.obj"));
    RunResult r;
    const Pfm image = render_scene(without_override("mtl.obj"), &r);
    expect_warning(r, "mtl.obj", "material file 'nothere.mtl' not found beside the OBJ");
    EXPECT_EQ(image.rgb, plain.rgb);
    EXPECT_GT(*std::max_element(image.rgb.begin(), image.rgb.end()), 0.05f);
}

}  // namespace
