// The PLY loader on files written here in all three encodings, on hostile
// headers and bodies, and against the OBJ loader on the dragon.
#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <cstring>

#include "io/mesh_file.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using testing::shared_dir;
using testing::TempFolder;

enum class Encoding { Ascii, LittleEndian, BigEndian };

// One typed value of a PLY record: 'b' uchar, 'i' int, 'f' float, 'd' double.
struct Value {
    char type;
    double value;
};
Value uc(double v) { return {'b', v}; }
Value i32(double v) { return {'i', v}; }
Value f32(double v) { return {'f', v}; }
Value f64(double v) { return {'d', v}; }
using Record = std::vector<Value>;

template <class T>
void put_binary(std::string& out, T value, bool big_endian) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (big_endian != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

// A whole PLY file: `elements` is the header between the format line and
// end_header; each record becomes one ascii line or its binary bytes.
std::string ply_file(Encoding encoding, const std::string& elements, const std::vector<Record>& records) {
    const char* format = encoding == Encoding::Ascii          ? "ascii"
                         : encoding == Encoding::LittleEndian ? "binary_little_endian"
                                                              : "binary_big_endian";
    std::string out =
        std::string("ply\nformat ") + format + " 1.0\ncomment written by sombra's tests\n" + elements + "end_header\n";
    const bool big = encoding == Encoding::BigEndian;
    for (const Record& record : records) {
        for (const Value& v : record) {
            if (encoding == Encoding::Ascii) {
                char text[40];
                std::snprintf(text, sizeof text, "%.17g ", v.value);
                out += text;
            } else if (v.type == 'b') {
                out += static_cast<char>(static_cast<unsigned char>(v.value));
            } else if (v.type == 'i') {
                put_binary(out, static_cast<std::int32_t>(v.value), big);
            } else if (v.type == 'f') {
                put_binary(out, static_cast<float>(v.value), big);
            } else {
                put_binary(out, v.value, big);
            }
        }
        if (encoding == Encoding::Ascii) out += "\n";
    }
    return out;
}

// A square (a quad) and a triangle to an apex above it.
const std::string kSquareHeader =
    "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\n";
const std::vector<Record> kSquareRecords = {
    {f32(0), f32(0), f32(0)},        {f32(1), f32(0), f32(0)},        {f32(1), f32(1), f32(0)},
    {f32(0), f32(1), f32(0)},        {f32(0.5), f32(0.5), f32(1.25)}, {uc(4), i32(0), i32(1), i32(2), i32(3)},
    {uc(3), i32(0), i32(1), i32(4)},
};
const std::vector<Vec3> kSquarePositions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 1.25f}};
const std::vector<Index3> kSquareTriangles = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}};

constexpr Encoding kEncodings[] = {Encoding::Ascii, Encoding::LittleEndian, Encoding::BigEndian};

LoadedMesh load_text(const TempFolder& tmp, const std::string& bytes, Diagnostics& diag) {
    return load_ply(tmp.write("test.ply", bytes), diag);
}

// The Error load_ply throws for `bytes` (a failure when it throws none).
Error error_for(const TempFolder& tmp, const std::string& bytes) {
    Diagnostics diag;
    try {
        load_text(tmp, bytes, diag);
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "loaded without an error";
    return Error("", "");
}

TEST(PlyLoader, SameMeshInEveryEncoding) {
    TempFolder tmp;
    for (Encoding encoding : kEncodings) {
        Diagnostics diag;
        const LoadedMesh loaded = load_text(tmp, ply_file(encoding, kSquareHeader, kSquareRecords), diag);
        EXPECT_EQ(loaded.mesh.positions, kSquarePositions);
        EXPECT_EQ(loaded.mesh.triangles, kSquareTriangles);
        EXPECT_FALSE(loaded.mesh.has_normals());
        ASSERT_EQ(loaded.materials.size(), 1u);
        EXPECT_EQ(loaded.materials[0].kd, default_material().kd);
        EXPECT_EQ(loaded.mesh.material_ids, std::vector<std::uint32_t>(3, 0));
        EXPECT_TRUE(diag.warnings.empty());
    }
}

TEST(PlyLoader, SkipsOtherElementsAndProperties) {
    const std::string header =
        "element material 2\nproperty uchar r\nproperty list uchar float values\n"
        "element vertex 5\nproperty float x\nproperty uchar red\nproperty float y\n"
        "property list uchar int junk\nproperty float z\nproperty double confidence\n"
        "element face 2\nproperty uchar flags\nproperty list uchar int vertex_index\n"
        "property list uchar float texcoord\nproperty int id\n"
        "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
        "element nothing 4000000000\n";
    std::vector<Record> records = {{uc(7), uc(2), f32(1.5), f32(2.5)}, {uc(8), uc(0)}};
    for (const Vec3& p : kSquarePositions) {
        records.push_back({f32(p.x), uc(200), f32(p.y), uc(2), i32(-7), i32(9), f32(p.z), f64(0.25)});
    }
    records.push_back({uc(1), uc(4), i32(0), i32(1), i32(2), i32(3), uc(2), f32(0.5), f32(0.5), i32(11)});
    records.push_back({uc(1), uc(3), i32(0), i32(1), i32(4), uc(0), i32(12)});
    records.push_back({i32(0), i32(1)});
    TempFolder tmp;
    for (Encoding encoding : kEncodings) {
        Diagnostics diag;
        const LoadedMesh loaded = load_text(tmp, ply_file(encoding, header, records), diag);
        EXPECT_EQ(loaded.mesh.positions, kSquarePositions);
        EXPECT_EQ(loaded.mesh.triangles, kSquareTriangles);
    }
}

TEST(PlyLoader, DoubleCoordinatesAndNormals) {
    const std::string header =
        "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        "element face 1\nproperty list uchar uint vertex_indices\n";
    const std::vector<Record> records = {
        {f64(0.1), f64(0), f64(0), f32(0), f32(0), f32(2)},
        {f64(1), f64(0.2), f64(0), f32(0), f32(0), f32(0)},  // zero normal: that corner has none
        {f64(0), f64(1), f64(0.3), f32(0), f32(3), f32(4)},
        {uc(3), i32(0), i32(1), i32(2)},
    };
    TempFolder tmp;
    for (Encoding encoding : kEncodings) {
        Diagnostics diag;
        const TriangleMesh mesh = load_text(tmp, ply_file(encoding, header, records), diag).mesh;
        ASSERT_EQ(mesh.positions.size(), 3u);
        EXPECT_EQ(mesh.positions[0], Vec3(0.1f, 0, 0));
        EXPECT_EQ(mesh.positions[2], Vec3(0, 1, 0.3f));
        ASSERT_TRUE(mesh.has_normals());
        ASSERT_EQ(mesh.normals.size(), 2u);
        EXPECT_EQ(mesh.normals[0], Vec3(0, 0, 1));
        EXPECT_NEAR(mesh.normals[1].y, 0.6f, 1e-6f);
        EXPECT_NEAR(mesh.normals[1].z, 0.8f, 1e-6f);
        EXPECT_EQ(mesh.normal_indices[0], (Index3{0, kNoNormal, 1}));
    }
}

TEST(PlyLoader, FacesBeforeVerticesAndConcavePolygons) {
    // An L-shaped hexagon whose fan would overlap, its face before its vertices.
    const std::string header =
        "element face 1\nproperty list uchar int vertex_indices\n"
        "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n";
    const std::vector<Record> records = {
        {uc(6), i32(0), i32(1), i32(2), i32(3), i32(4), i32(5)},
        {f32(2), f32(0), f32(0)},
        {f32(2), f32(1), f32(0)},
        {f32(1), f32(1), f32(0)},
        {f32(1), f32(2), f32(0)},
        {f32(0), f32(2), f32(0)},
        {f32(0), f32(0), f32(0)},
    };
    TempFolder tmp;
    Diagnostics diag;
    const TriangleMesh mesh = load_text(tmp, ply_file(Encoding::LittleEndian, header, records), diag).mesh;
    ASSERT_EQ(mesh.triangle_count(), 4u);
    float total = 0;
    for (const Index3& c : mesh.triangles) {
        const float area =
            testing::twice_area_along(mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]], {0, 0, 1});
        EXPECT_GT(area, 0);
        total += area;
    }
    EXPECT_NEAR(total, 6.0f, 1e-5f);
}

TEST(PlyLoader, NonFiniteVerticesAreDropped) {
    TempFolder tmp;
    std::string text = ply_file(Encoding::Ascii, kSquareHeader, kSquareRecords);
    text.replace(text.find("1.25"), 4, "nan");
    Diagnostics diag;
    const TriangleMesh mesh = load_text(tmp, text, diag).mesh;
    EXPECT_EQ(mesh.triangle_count(), 2u);
    EXPECT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(diag.warnings.size(), 1u);
}

TEST(PlyLoader, HostileCountsFailFastWithoutAllocating) {
    TempFolder tmp;
    const std::string header =
        "element vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 4000000000\nproperty list uchar int vertex_indices\n";
    const std::vector<Record> body(8, Record{f32(1), f32(2), f32(3)});  // 96 bytes
    for (Encoding encoding : kEncodings) {
        const auto start = std::chrono::steady_clock::now();
        const Error e = error_for(tmp, ply_file(encoding, header, body));
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
        EXPECT_NE(e.message().find("4000000000"), std::string::npos) << e.what();
    }
    // A face list claiming two billion corners.
    const std::string list_header =
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list int int vertex_indices\n";
    const std::vector<Record> list_body = {{f32(0), f32(0), f32(0)},
                                           {f32(1), f32(0), f32(0)},
                                           {f32(0), f32(1), f32(0)},
                                           {i32(2000000000), i32(0), i32(1), i32(2)}};
    for (Encoding encoding : kEncodings) {
        const Error e = error_for(tmp, ply_file(encoding, list_header, list_body));
        EXPECT_NE(e.message().find("2000000000"), std::string::npos) << e.what();
    }
}

TEST(PlyLoader, TruncatedBodyFails) {
    TempFolder tmp;
    for (Encoding encoding : kEncodings) {
        std::string text = ply_file(encoding, kSquareHeader, kSquareRecords);
        text.resize(text.size() - 6);
        const Error e = error_for(tmp, text);
        EXPECT_NE(e.message().find("end of file"), std::string::npos) << e.what();
        if (encoding != Encoding::Ascii) {
            EXPECT_NE(e.message().find("byte offset"), std::string::npos) << e.what();
        }
    }
}

TEST(PlyLoader, BadIndicesFailWithTheirPlace) {
    TempFolder tmp;
    std::vector<Record> records = kSquareRecords;
    records[6] = {uc(3), i32(0), i32(5), i32(4)};  // 5 vertices: index 5 is one too many
    for (Encoding encoding : kEncodings) {
        const Error e = error_for(tmp, ply_file(encoding, kSquareHeader, records));
        EXPECT_NE(e.message().find("vertex index 5 out of range"), std::string::npos) << e.what();
        // Ascii: header (10 lines), 5 vertex lines, then the second face on line 17.
        if (encoding == Encoding::Ascii) {
            EXPECT_EQ(e.where(), (tmp.path / "test.ply").string() + ":17");
        }
    }
    records[6] = {uc(3), i32(0), i32(-1), i32(4)};
    for (Encoding encoding : kEncodings) {
        EXPECT_NE(error_for(tmp, ply_file(encoding, kSquareHeader, records)).message().find("out of range"),
                  std::string::npos);
    }
}

TEST(PlyLoader, HeaderErrorsNameTheirLine) {
    TempFolder tmp;
    const std::string file = (tmp.path / "test.ply").string();
    const std::string vertex = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
    const struct {
        std::string text;
        int line;
    } cases[] = {
        {"plx\nformat ascii 1.0\nend_header\n", 1},
        {"ply\nformat utf8 1.0\nend_header\n", 2},
        {"ply\nformat ascii 2.0\nend_header\n", 2},
        {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", 3},
        {"ply\nformat ascii 1.0\n" + vertex + "property float32x y\nend_header\n", 7},
        {"ply\nformat ascii 1.0\nelement vertex -5\nend_header\n", 3},
        {"ply\nformat ascii 1.0\n" + vertex, 7},  // no end_header
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", 3},
        {"ply\nformat ascii 1.0\n" + vertex + "element face 1\nproperty int vertex_indices\nend_header\n0 0 0\n1\n", 7},
    };
    for (const auto& c : cases) {
        const Error e = error_for(tmp, c.text);
        EXPECT_EQ(e.where(), file + ":" + std::to_string(c.line)) << c.text << "\n→ " << e.what();
    }
    EXPECT_EQ(error_for(tmp, "ply\nformat ascii 1.0\nelement face 0\nend_header\n").where(), file);
}

TEST(PlyLoader, NoFacesIsNoTriangles) {
    TempFolder tmp;
    const std::string header = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
    const Error e = error_for(tmp, ply_file(Encoding::LittleEndian, header, {{f32(1), f32(2), f32(3)}}));
    EXPECT_NE(e.message().find("no triangles"), std::string::npos) << e.what();
}

TEST(PlyLoader, DispatchIsCaseInsensitive) {
    TempFolder tmp;
    Diagnostics diag;
    const auto path = tmp.write("SQUARE.PLY", ply_file(Encoding::BigEndian, kSquareHeader, kSquareRecords));
    EXPECT_EQ(load_mesh_file(path, diag).mesh.triangles, kSquareTriangles);
}

TEST(PlyLoader, DragonPlyMatchesDragonObj) {
    SOMBRA_REQUIRE_SHARED("models/dragon.ply");
    Diagnostics diag;
    const auto t0 = std::chrono::steady_clock::now();
    const TriangleMesh ply = load_ply(shared_dir() / "models/dragon.ply", diag).mesh;
    const auto t1 = std::chrono::steady_clock::now();
    const TriangleMesh obj = load_obj(shared_dir() / "models/dragon.obj", diag).mesh;
    const auto t2 = std::chrono::steady_clock::now();
    std::printf("[ timing ] dragon.ply %.3f s, dragon.obj %.3f s\n", std::chrono::duration<double>(t1 - t0).count(),
                std::chrono::duration<double>(t2 - t1).count());
    EXPECT_TRUE(diag.warnings.empty());
    EXPECT_EQ(ply.triangle_count(), 871414u);
    EXPECT_EQ(ply.positions.size(), 437645u);
    EXPECT_TRUE(ply.positions == obj.positions);
    EXPECT_TRUE(ply.triangles == obj.triangles);
}

}  // namespace
}  // namespace sombra
