// sombra's OBJ parser: numbers rounded as strtof rounds them, tinyobjloader's
// outcome on malformed numbers and indices, and the same result for any
// split into chunks and any thread count.
#include "io/obj/obj_parse.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#include "core/error.h"
#include "io/polygon_test_files.h"
#include "scene/mesh.h"

namespace sombra {
namespace {

// read_obj_real on the whole of `text`; NaN marks "tinyobjloader fails".
float real(std::string_view text, std::size_t* read = nullptr) {
    float value = std::numeric_limits<float>::quiet_NaN();
    const char* end = read_obj_real(text.data(), text.data() + text.size(), value);
    if (read) *read = end ? std::size_t(end - text.data()) : 0;
    return end ? value : std::numeric_limits<float>::quiet_NaN();
}

TEST(ObjRealNumbers, MatchStrtofBitForBitOnDragonCoordinates) {
    SOMBRA_REQUIRE_SHARED("models");
    std::ifstream in(testing::shared_dir() / "models/dragon.obj", std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::size_t numbers = 0, begin = 0;
    while (begin < text.size()) {
        std::size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        if (text.compare(begin, 2, "v ") == 0 || text.compare(begin, 3, "vn ") == 0) {
            std::size_t i = text.find(' ', begin) + 1;
            while (i < end) {
                std::size_t j = text.find_first_of(" \r\n", i);
                if (j == std::string::npos || j > end) j = end;
                const std::string token = text.substr(i, j - i);
                std::size_t read = 0;
                const float ours = real(token, &read);
                const float theirs = std::strtof(token.c_str(), nullptr);
                ASSERT_EQ(read, token.size()) << token;
                ASSERT_EQ(std::bit_cast<std::uint32_t>(ours), std::bit_cast<std::uint32_t>(theirs)) << token;
                ++numbers;
                i = j + 1;
            }
        }
        begin = end + 1;
    }
    EXPECT_GT(numbers, 1'300'000u);  // 437,645 vertices
}

TEST(ObjRealNumbers, MatchStrtofOnHardCases) {
    // Halfway cases, denormals, the float range's edges, long mantissas.
    for (const char* text :
         {"1.00000005960464477539062",
          "1.000000059604644775390625",
          "1.00000017881393432617187499",
          "3.4028235e38",
          "3.40282356779733661637539395458142568448e38",
          "3.4028236e38",
          "1e-45",
          "7e-46",
          "7.1e-46",
          "1.17549435e-38",
          "0.000000000000000000000000000000000000000000001",
          "123456789012345678901234567890",
          "-0",
          "-0.0e5",
          "1e999",
          "-1e999",
          "1e-999",
          "-1e-999",
          "4.9406564584124654e-324",
          "1.8e308",
          "2e400",
          ".000000000000000000000000000000000000000000000000000000000000000000000000000000001e-300"}) {
        const float ours = real(text);
        const float theirs = std::strtof(text, nullptr);
        EXPECT_EQ(std::bit_cast<std::uint32_t>(ours), std::bit_cast<std::uint32_t>(theirs)) << text;
    }
}

TEST(ObjRealNumbers, AcceptWhatTinyobjloaderAccepts) {
    std::size_t read = 0;
    EXPECT_EQ(real("3.1+e2", &read), 3.1f);  // assimp's number_formats.obj: the number ends at '+'
    EXPECT_EQ(read, 3u);
    EXPECT_EQ(real("1.#IND", &read), 1.0f);
    EXPECT_EQ(read, 2u);
    EXPECT_EQ(real("+1"), 1.0f);
    EXPECT_EQ(real("2."), 2.0f);
    EXPECT_EQ(real("2.e1"), 20.0f);
    EXPECT_EQ(real("+2.e+1"), 20.0f);
    EXPECT_EQ(real(".8e-001"), 0.08f);
    EXPECT_EQ(real("-.7e+02"), -70.0f);
    EXPECT_EQ(real("."), 0.0f);
    EXPECT_TRUE(std::signbit(real("-.")));
    EXPECT_EQ(real(".e5"), 0.0f);
    // tinyobjloader fails on these, and the caller takes its default.
    for (const char* text : {"", "nan", "inf", "-inf", "+", "-", "e5", "1e", "1e+", "1E-", "1e9999999999", "#"}) {
        EXPECT_TRUE(std::isnan(real(text))) << text;
    }
    EXPECT_EQ(real("1e000000000000000000001"), 10.0f);  // leading zeros are no overflow
}

TEST(ObjAtoi, AsGlibcComputesIt) {
    auto atoi_of = [](std::string_view s) { return obj_atoi(s.data(), s.data() + s.size()); };
    for (const char* text : {"12", "-7", "+5", " \t\v\f 42x", "/3", "", "-", "2147483647", "-2147483648", "2147483648",
                             "4294967298", "99999999999999999999", "-99999999999999999999"}) {
        EXPECT_EQ(atoi_of(text), std::atoi(text)) << text;
    }
}

// Everything parse_obj returns, flattened for comparison.
std::vector<std::string> flatten(const ObjGeometry& g) {
    std::vector<std::string> out;
    for (const Vec3& p : g.positions)
        out.push_back("v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z));
    for (const Vec3& n : g.normals)
        out.push_back("vn " + std::to_string(n.x) + " " + std::to_string(n.y) + " " + std::to_string(n.z));
    for (const ObjFaceBlock& block : g.faces) {
        std::uint32_t begin = 0;
        for (std::uint32_t end : block.ends) {
            std::string face = "f";
            for (std::uint32_t k = begin; k < end; ++k)
                face.append(" ")
                    .append(std::to_string(block.positions[k]))
                    .append("/")
                    .append(std::to_string(block.normals[k]));
            out.push_back(face);
            begin = end;
        }
    }
    for (const ObjDirective& d : g.directives)
        out.push_back("d " + std::to_string(d.line) + " " + std::to_string(d.face) + " " + std::string(d.text));
    out.push_back("small " + std::to_string(g.small_faces) + " bad " + std::to_string(g.bad_normal_refs));
    return out;
}

// A file with every line ending, relative indices reaching into earlier
// chunks, materials between faces, a NUL-cut line and a face of 2 corners.
std::string mixed_file() {
    std::string text = "mtllib a.mtl\r\n";
    for (int i = 0; i < 40; ++i) {
        text += "v " + std::to_string(i) + " " + std::to_string(i % 7) + ".5 -" + std::to_string(i) + "e-1";
        text += i % 3 == 0 ? "\r\n" : (i % 3 == 1 ? "\r" : "\n");
        if (i % 5 == 4) text += "vn 0 0 1\nusemtl  m" + std::to_string(i) + " x \n";
        if (i >= 3) text += "f -1 -2//-1 -3/1/1\n\tf " + std::to_string(i) + " " + std::to_string(i - 1) + "\n";
    }
    text += std::string_view("f 1 2 3 4\0 5 6\nf 1//1 2//9 3//1", 31);
    return text;
}

TEST(ObjParse, SameResultForEveryChunkSizeAndThreadCount) {
    const std::string text = mixed_file();
    const std::vector<std::string> reference = flatten(parse_obj(text, "m.obj", text.size() + 1));
    ASSERT_EQ(reference.size(), 40u + 8u + 37u + 2u + 8u + 1u + 1u);
    for (std::size_t chunk : {std::size_t(1), std::size_t(2), std::size_t(7), std::size_t(64), std::size_t(1) << 19}) {
        for (int threads : {1, 2, 4}) {
            tbb::task_arena arena(threads);
            arena.execute([&] { EXPECT_EQ(flatten(parse_obj(text, "m.obj", chunk)), reference) << chunk; });
        }
    }
    const ObjGeometry g = parse_obj(text, "m.obj");
    EXPECT_EQ(g.small_faces, 37u);                    // the "f i i-1" lines
    EXPECT_EQ(g.bad_normal_refs, 1u);                 // 2//9
    EXPECT_EQ(g.directives[1].text, "m4 x");          // the rest of the line, trimmed
    EXPECT_EQ(g.faces.back().ends.size(), 37u + 2u);  // the NUL cuts "5 6" off: a quad
    EXPECT_EQ(g.positions[1], Vec3(1, 1.5f, -0.1f));
}

TEST(ObjParse, ErrorsNameTheLineAcrossChunks) {
    const std::string text = "v 0 0 0\rv 1 0 0\r\nv 0 1 0\n\n# c\nf 1 2 3\nf -1 -2 -4\nf 1 2 0\n";
    for (std::size_t chunk : {std::size_t(1), std::size_t(5), std::size_t(1) << 19}) {
        try {
            parse_obj(text, "e.obj", chunk);
            ADD_FAILURE() << chunk;
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), "e.obj:7") << chunk;
            EXPECT_EQ(e.message(), "face index -4 out of range (counting back from the 3 vertices before it)");
        }
    }
    // tinyobjloader's failures come after the index problems, wherever they are.
    auto error_of = [](const std::string& obj) {
        try {
            parse_obj(obj, "e.obj", 4);
        } catch (const Error& e) {
            return e.where() + ": " + e.message();
        }
        return std::string("loaded");
    };
    EXPECT_EQ(error_of("v 0 0 0\nf 1 1/ 1/\nf 1 1 9999999999\n"),
              "e.obj:3: face index 9999999999 out of range (the file has 1 vertex)");
    EXPECT_EQ(error_of("v 0 0 0\nf 1 1 1/\nf 1 1 2\n"),
              "e.obj:2: face corner '1/' is not made of indices (v, v/vt, v//vn or v/vt/vn)");
    EXPECT_EQ(error_of("v 0 0 0\nl 1 0\n"), "e.obj:2: `l` line: an index is 0 or not a number");
    EXPECT_EQ(error_of("v 0 0 0\nf 1 1 2\nf 1 1/2/3/4 1\n"),
              "e.obj:3: face corner '1/2/3/4' is not made of indices (v, v/vt, v//vn or v/vt/vn)");
    EXPECT_EQ(error_of("v 0 0 0\nf 1 1 2\nf 1 1 1\n"), "e.obj:2: face index 2 out of range (the file has 1 vertices)");
    EXPECT_EQ(error_of("v 0 0 0\nf 1 2\nf 1 1 1\n"), "loaded");  // small faces are not checked
}

TEST(ObjParse, CoordinatesAsTinyobjloaderReadThem) {
    const ObjGeometry g =
        parse_obj("v 1 2\nv nan 0 0\nv 1 1 1.#IND\nv 3.1+e2 1e 1e999\nv\t-.5\t+2 .e1 7 8\nvn nan 1 2\n", "c.obj");
    ASSERT_EQ(g.positions.size(), 5u);
    EXPECT_EQ(g.positions[0], Vec3(1, 2, 0));  // a missing coordinate is 0
    EXPECT_TRUE(std::isnan(g.positions[1].x));
    EXPECT_TRUE(std::isnan(g.positions[2].z));
    EXPECT_EQ(g.positions[3].x, 3.1f);
    EXPECT_EQ(g.positions[3].y, 0.0f);
    EXPECT_TRUE(std::isinf(g.positions[3].z));
    EXPECT_EQ(g.positions[4], Vec3(-0.5f, 2, 0));
    EXPECT_EQ(g.normals.at(0), Vec3(0, 1, 2));  // not a position: "nan" is tinyobjloader's 0
}

}  // namespace
}  // namespace sombra
