// Binary PLY bodies are read in slices (ply_binary_stream.h), not whole:
// meshes larger than several slices, values that straddle slice
// boundaries, headers longer than one read, and truncation past the first
// slice give what reading the whole file gave.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>

#include "io/mesh_file.h"
#include "io/ply/ply_binary_stream.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using testing::TempFolder;

// An n × n grid of squares, two triangles each, with a bump so that no two
// rows of positions are alike: as ascii, or as binary little endian (float
// x y z; uchar-counted int lists: 13-byte faces, so faces straddle slices).
std::string grid_ply(int n, bool binary, const std::string& comments = "") {
    const int side = n + 1;
    std::string out = std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") + " 1.0\n" + comments +
                      "element vertex " + std::to_string(side * side) +
                      "\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face " +
                      std::to_string(2 * n * n) + "\nproperty list uchar int vertex_indices\nend_header\n";
    auto put = [&](auto value) {
        char bytes[sizeof value];
        std::memcpy(bytes, &value, sizeof value);
        out.append(bytes, sizeof value);
    };
    for (int y = 0; y < side; ++y) {
        for (int x = 0; x < side; ++x) {
            const float p[3] = {float(x) * 0.25f, float(y) * 0.5f, float((x * 7 + y * 3) % 11) * 0.125f};
            if (binary) {
                for (float c : p) put(c);
            } else {
                out += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
            }
        }
    }
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const std::int32_t a = y * side + x, b = a + 1, c = a + side, d = c + 1;
            for (const std::array<std::int32_t, 3>& t :
                 {std::array<std::int32_t, 3>{a, b, d}, std::array<std::int32_t, 3>{a, d, c}}) {
                if (binary) {
                    put(std::uint8_t{3});
                    for (int k = 0; k < 3; ++k) put(t[k]);
                } else {
                    out += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
                }
            }
        }
    }
    return out;
}

LoadedMesh load(const TempFolder& tmp, const std::string& name, const std::string& bytes) {
    Diagnostics diag;
    return load_ply(tmp.write(name, bytes), diag);
}

TEST(PlyStream, MeshOfSeveralSlicesEqualsItsAsciiTwin) {
    TempFolder tmp;
    const std::string binary = grid_ply(300, true);
    ASSERT_GT(binary.size(), 3 * kPlyStreamSlice);  // 90,601 vertices, 180,000 faces
    const LoadedMesh from_binary = load(tmp, "grid.ply", binary);
    const LoadedMesh from_ascii = load(tmp, "grid-ascii.ply", grid_ply(300, false));
    ASSERT_EQ(from_binary.mesh.triangles.size(), 180000u);
    EXPECT_EQ(from_binary.mesh.positions, from_ascii.mesh.positions);
    EXPECT_EQ(from_binary.mesh.triangles, from_ascii.mesh.triangles);
    EXPECT_EQ(from_binary.mesh.material_ids, from_ascii.mesh.material_ids);
}

TEST(PlyStream, HeaderLongerThanOneRead) {
    TempFolder tmp;
    std::string comments;
    while (comments.size() < 200000) comments += "comment a header longer than the 64 KiB the loader reads at once\n";
    const LoadedMesh long_header = load(tmp, "long.ply", grid_ply(20, true, comments));
    const LoadedMesh short_header = load(tmp, "short.ply", grid_ply(20, true));
    EXPECT_EQ(long_header.mesh.positions, short_header.mesh.positions);
    EXPECT_EQ(long_header.mesh.triangles, short_header.mesh.triangles);
}

TEST(PlyStream, TruncationPastTheFirstSliceNamesItsOffset) {
    TempFolder tmp;
    std::string bytes = grid_ply(300, true);
    const std::size_t size = bytes.size();
    // Five bytes short: the last face's count (3) is read 13 bytes before
    // the original end; its three indices no longer fit after it.
    bytes.resize(size - 5);
    Diagnostics diag;
    try {
        load_ply(tmp.write("cut.ply", bytes), diag);
        ADD_FAILURE() << "loaded a truncated file";
    } catch (const Error& e) {
        EXPECT_EQ(e.message(), "face 179999 claims 3 corners, more than fit before the end of file (byte offset " +
                                   std::to_string(size - 12) + ")");
    }
}

}  // namespace
}  // namespace sombra
