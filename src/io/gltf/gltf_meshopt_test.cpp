// EXT_meshopt_compression (spec §24): a mesh compressed in the test with
// meshoptimizer's own encoders loads to the same triangles as the plain
// file, bit for bit where the decoded bytes are the plain ones, within the
// quantisation's bound through the octahedral, quaternion and exponential
// filters; broken extension data is one error line, never a crash.
#include <gtest/gtest.h>

#include <meshoptimizer.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "core/base64.h"
#include "io/gltf/gltf_meshopt.h"
#include "io/gltf/gltf_test_files.h"
#include "io/mesh_file.h"
#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

// A bumpy n × n grid of vertices: positions, unit normals, uvs, and two
// triangles per cell.
struct Grid {
    std::vector<Vec3> positions, normals;
    std::vector<Vec2> uvs;
    std::vector<std::uint32_t> indices;
};

Grid make_grid(int n) {
    Grid g;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x = float(i) / float(n - 1), y = float(j) / float(n - 1);
            g.positions.push_back({x * 3.0f - 1.5f, y * 2.0f, 0.25f * std::sin(7.0f * x) * std::cos(5.0f * y)});
            g.normals.push_back(normalize(Vec3{std::sin(3.0f * x), std::cos(4.0f * y), 1.5f}));
            g.uvs.push_back({x, y});
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const auto v = std::uint32_t(j * n + i), w = std::uint32_t(n);
            for (std::uint32_t k : {v, v + 1, v + w + 1, v, v + w + 1, v + w}) g.indices.push_back(k);
        }
    return g;
}

// The compressed twin of a file: its compressed bytes in buffer 0, the
// buffer views' uncompressed places in fallback buffer 1 (no data).
struct Packed {
    GltfFile file;
    std::size_t fallback_bytes = 0;

    // A view holding `count` elements of `stride` bytes, compressed as
    // `mode` ("ATTRIBUTES": `data` is the raw elements; "TRIANGLES",
    // "INDICES": `data` is uint32 indices stored as `stride`-byte integers).
    int add_view(const void* data, std::size_t count, std::size_t stride, const std::string& mode,
                 const std::string& filter = "NONE") {
        std::vector<unsigned char> encoded;
        std::size_t size = 0;
        const auto* indices = static_cast<const unsigned int*>(data);
        if (mode == "ATTRIBUTES") {
            encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
            size = meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, count, stride);
        } else if (mode == "TRIANGLES") {
            encoded.resize(meshopt_encodeIndexBufferBound(count, count));
            size = meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices, count);
        } else {
            encoded.resize(meshopt_encodeIndexSequenceBound(count, count));
            size = meshopt_encodeIndexSequence(encoded.data(), encoded.size(), indices, count);
        }
        EXPECT_GT(size, 0u);
        while (file.bin.size() % 4 != 0) file.bin.push_back('\0');
        const std::size_t offset = file.bin.size();
        file.bin.append(reinterpret_cast<const char*>(encoded.data()), size);
        nlohmann::json ext = {{"buffer", 0},          {"byteOffset", offset}, {"byteLength", size},
                              {"byteStride", stride}, {"count", count},       {"mode", mode}};
        if (filter != "NONE") ext["filter"] = filter;
        nlohmann::json view = {{"buffer", 1},
                               {"byteOffset", fallback_bytes},
                               {"byteLength", count * stride},
                               {"extensions", {{kMeshoptName, ext}}}};
        if (mode == "ATTRIBUTES") view["byteStride"] = stride;
        fallback_bytes += (count * stride + 3) / 4 * 4;
        file.doc["bufferViews"].push_back(view);
        return int(file.doc["bufferViews"].size()) - 1;
    }

    // The file as .gltf (compressed bytes as a data URI) or .glb (the BIN chunk).
    std::filesystem::path save(const TempFolder& dir, const std::string& name) {
        const bool glb = name.ends_with(".glb");
        nlohmann::json compressed = {{"byteLength", file.bin.size()}};
        if (!glb) compressed["uri"] = "data:application/octet-stream;base64," + base64_encode(file.bin);
        file.doc["buffers"] = {
            compressed, {{"byteLength", fallback_bytes}, {"extensions", {{kMeshoptName, {{"fallback", true}}}}}}};
        return dir.write(name, glb ? file.glb() : file.gltf());
    }

    static constexpr const char* kMeshoptName = "EXT_meshopt_compression";
};

template <class T>
std::vector<std::uint16_t> narrowed(const std::vector<T>& v) {
    return {v.begin(), v.end()};
}

// The grid as a plain file and as its compressed twin: positions, normals and
// uvs as ATTRIBUTES, indices as `index_mode` of `index_stride`-byte integers.
std::pair<GltfFile, Packed> twins(const Grid& g, const std::string& index_mode, std::size_t index_stride) {
    GltfFile plain;
    Packed packed;
    packed.file.use_extension(Packed::kMeshoptName, true);
    const int component = index_stride == 2 ? gltf_test::kUnsignedShort : gltf_test::kUnsignedInt;
    for (GltfFile* f : {&plain, &packed.file}) {
        const bool is_plain = f == &plain;
        const int p = is_plain ? plain.add_view(g.positions.data(), g.positions.size() * 12, 12)
                               : packed.add_view(g.positions.data(), g.positions.size(), 12, "ATTRIBUTES");
        const int n = is_plain ? plain.add_view(g.normals.data(), g.normals.size() * 12, 12)
                               : packed.add_view(g.normals.data(), g.normals.size(), 12, "ATTRIBUTES");
        const int uv = is_plain ? plain.add_view(g.uvs.data(), g.uvs.size() * 8, 8)
                                : packed.add_view(g.uvs.data(), g.uvs.size(), 8, "ATTRIBUTES");
        const std::vector<std::uint16_t> short_indices = narrowed(g.indices);
        const int i = is_plain ? (index_stride == 2 ? plain.add_view(short_indices.data(), short_indices.size() * 2)
                                                    : plain.add_view(g.indices.data(), g.indices.size() * 4))
                               : packed.add_view(g.indices.data(), g.indices.size(), index_stride, index_mode);
        f->add_accessor(p, gltf_test::kFloat, g.positions.size(), "VEC3");
        f->add_accessor(n, gltf_test::kFloat, g.normals.size(), "VEC3");
        f->add_accessor(uv, gltf_test::kFloat, g.uvs.size(), "VEC2");
        f->add_accessor(i, component, g.indices.size(), "SCALAR");
        // TEXCOORD_1 (spec §24) reads the compressed view too.
        f->add_mesh({{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"TEXCOORD_1", 2}}, 3);
        f->add_node({{"mesh", 0}});
        f->set_scene({0});
    }
    return {plain, packed};
}

// The same triangles in the same order and winding; TRIANGLES' codec may
// start each at another corner (it rotates them to compress better), the
// other modes give them back exactly.
template <class Triangles>
void expect_same_triangles(const Triangles& a, const Triangles& b, bool exact) {
    if (exact) {
        EXPECT_EQ(a, b);
        return;
    }
    ASSERT_EQ(a.size(), b.size());
    std::size_t rotated = 0;
    for (std::size_t t = 0; t < a.size(); ++t) {
        bool same = false;
        for (int r = 0; r < 3 && !same; ++r)
            same = a[t][0] == b[t][r] && a[t][1] == b[t][(r + 1) % 3] && a[t][2] == b[t][(r + 2) % 3];
        EXPECT_TRUE(same) << "triangle " << t;
        rotated += a[t] == b[t] ? 0 : 1;
    }
    EXPECT_GT(rotated, 0u);  // else this test would not see the difference
}

void expect_same_mesh(const LoadedMesh& a, const LoadedMesh& b, bool exact_triangles) {
    EXPECT_EQ(a.mesh.positions, b.mesh.positions);
    expect_same_triangles(a.mesh.triangles, b.mesh.triangles, exact_triangles);
    EXPECT_EQ(a.mesh.normals, b.mesh.normals);
    EXPECT_EQ(a.mesh.uvs, b.mesh.uvs);
    expect_same_triangles(a.mesh.uv_indices, b.mesh.uv_indices, exact_triangles);
    expect_same_triangles(a.mesh.normal_indices, b.mesh.normal_indices, exact_triangles);
    EXPECT_EQ(a.mesh.extra_uvs[0].uvs, b.mesh.extra_uvs[0].uvs);
    expect_same_triangles(a.mesh.extra_uvs[0].indices, b.mesh.extra_uvs[0].indices, exact_triangles);
}

TEST(GltfMeshopt, EveryModeLoadsTheSameTrianglesAsThePlainFile) {
    const Grid g = make_grid(12);
    const struct {
        const char* mode;
        std::size_t stride;
        const char* name;
    } cases[] = {{"TRIANGLES", 2, "tri16.gltf"},
                 {"TRIANGLES", 4, "tri32.glb"},
                 {"INDICES", 2, "seq16.glb"},
                 {"INDICES", 4, "seq32.gltf"}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        auto [plain, packed] = twins(g, c.mode, c.stride);
        TempFolder dir;
        Diagnostics plain_diag, diag;
        const LoadedMesh a = load_gltf(dir.write("plain.gltf", plain.gltf()), plain_diag);
        const LoadedMesh b = load_gltf(packed.save(dir, c.name), diag);
        EXPECT_EQ(b.mesh.triangles.size(), g.indices.size() / 3);
        EXPECT_EQ(b.mesh.extra_uvs[0].uvs, b.mesh.uvs);
        expect_same_mesh(a, b, std::string(c.mode) == "INDICES");
        EXPECT_TRUE(diag.warnings.empty()) << diag.warnings.front();
    }
}

// Optional, with the uncompressed data still in the fallback buffer: the
// compressed views are read, and give the same mesh.
TEST(GltfMeshopt, AnOptionalExtensionWithRealFallbackDataLoadsTheSame) {
    const Grid g = make_grid(6);
    auto [plain, packed] = twins(g, "TRIANGLES", 4);
    packed.file.doc.erase("extensionsRequired");
    TempFolder dir;
    Diagnostics diag;
    const LoadedMesh a = load_gltf(dir.write("plain.gltf", plain.gltf()), diag);
    packed.save(dir, "unused.gltf");
    // The fallback buffer gets the plain file's bytes, laid out as the views say.
    nlohmann::json& buffers = packed.file.doc["buffers"];
    std::string fallback(packed.fallback_bytes, '\0');
    for (std::size_t v = 0; v < 4; ++v) {
        const nlohmann::json& pv = plain.doc["bufferViews"][v];
        const auto at = packed.file.doc["bufferViews"][v]["byteOffset"].get<std::size_t>();
        const auto length = pv["byteLength"].get<std::size_t>();
        fallback.replace(at, length, plain.bin, pv["byteOffset"].get<std::size_t>(), length);
    }
    buffers[1]["uri"] = "data:application/octet-stream;base64," + base64_encode(fallback);
    buffers[1].erase("extensions");
    const LoadedMesh b = load_gltf(dir.write("optional.gltf", packed.file.gltf()), diag);
    expect_same_mesh(a, b, false);
}

// Normals through the octahedral filter (8 and 16 bits) and positions through
// the exponential one: within the quantisation's bound of the plain floats.
TEST(GltfMeshopt, FilteredAttributesLoadWithinTheQuantisationBound) {
    const Grid g = make_grid(9);
    for (const int oct_bits : {8, 16}) {
        SCOPED_TRACE(oct_bits);
        auto [plain, unused] = twins(g, "TRIANGLES", 4);
        Packed packed;
        packed.file.use_extension(Packed::kMeshoptName, true);
        packed.file.use_extension("KHR_mesh_quantization", true);
        const std::size_t n = g.positions.size();
        constexpr int kExpBits = 16;
        std::vector<std::uint32_t> exp(n * 3);
        meshopt_encodeFilterExp(exp.data(), n, 12, kExpBits, &g.positions[0].x);
        const std::size_t oct_stride = oct_bits == 8 ? 4 : 8;
        std::vector<float> normals4;
        for (const Vec3& v : g.normals) normals4.insert(normals4.end(), {v.x, v.y, v.z, 0.0f});
        std::vector<unsigned char> oct(n * oct_stride);
        meshopt_encodeFilterOct(oct.data(), n, oct_stride, oct_bits, normals4.data());
        const int p = packed.add_view(exp.data(), n, 12, "ATTRIBUTES", "EXPONENTIAL");
        const int nv = packed.add_view(oct.data(), n, oct_stride, "ATTRIBUTES", "OCTAHEDRAL");
        const int uv = packed.add_view(g.uvs.data(), n, 8, "ATTRIBUTES");
        const int i = packed.add_view(g.indices.data(), g.indices.size(), 4, "TRIANGLES");
        packed.file.add_accessor(p, gltf_test::kFloat, n, "VEC3");
        packed.file.add_accessor(nv, oct_bits == 8 ? gltf_test::kByte : gltf_test::kShort, n, "VEC3", true);
        packed.file.add_accessor(uv, gltf_test::kFloat, n, "VEC2");
        packed.file.add_accessor(i, gltf_test::kUnsignedInt, g.indices.size(), "SCALAR");
        packed.file.add_mesh({{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}, 3);
        packed.file.add_node({{"mesh", 0}});
        packed.file.set_scene({0});

        TempFolder dir;
        Diagnostics diag;
        const LoadedMesh a = load_gltf(dir.write("plain.gltf", plain.gltf()), diag);
        const LoadedMesh b = load_gltf(packed.save(dir, "filtered.glb"), diag);
        expect_same_triangles(a.mesh.triangles, b.mesh.triangles, false);
        EXPECT_EQ(a.mesh.uvs, b.mesh.uvs);
        ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
        ASSERT_EQ(a.mesh.normals.size(), b.mesh.normals.size());
        // Exponential: one exponent per vertex, the largest frexp exponent of
        // its components (0's is 0), and a kExpBits-bit signed mantissa: the
        // error is at most half a step of 2^(e − (kExpBits − 1)).
        for (std::size_t k = 0; k < n; ++k) {
            const Vec3 v = a.mesh.positions[k];
            int e = -100;
            for (const float x : {v.x, v.y, v.z}) {
                int ex = 0;
                std::frexp(x, &ex);
                e = std::max(e, ex);
            }
            const float half_step = std::ldexp(1.0f, e - kExpBits);
            EXPECT_LE(max_component(abs(v - b.mesh.positions[k])), half_step) << k;
        }
        // Octahedral: the angle to the original normal within the grid of
        // 2^bits steps over the octahedron (and the SHORT or BYTE rounding).
        const float bound = oct_bits == 8 ? 0.03f : 3e-4f;
        float worst = 0.0f, sum = 0.0f;
        for (std::size_t k = 0; k < n; ++k) {
            const float e = length(normalize(a.mesh.normals[k]) - normalize(b.mesh.normals[k]));
            worst = std::max(worst, e);
            sum += e;
        }
        EXPECT_LE(worst, bound);
        EXPECT_GT(sum, 0.0f);  // quantised: not merely the plain bytes
    }
}

// The quaternion filter, decoded in place of a buffer view: unit
// quaternions come back within the 12-bit encoding's bound.
TEST(GltfMeshopt, QuaternionFilterDecodesUnitQuaternions) {
    const std::vector<float> quats = {0, 0,    0, 1,     0.5f, 0.5f, 0.5f, 0.5f, 0.6f, 0,
                                      0, 0.8f, 0, -0.8f, 0,    0.6f, 0.1f, 0.2f, 0.3f, 0.927362f};
    const std::size_t count = quats.size() / 4;
    std::vector<std::int16_t> encoded(count * 4);
    meshopt_encodeFilterQuat(encoded.data(), count, 8, 12, quats.data());
    std::vector<unsigned char> compressed(meshopt_encodeVertexBufferBound(count, 8));
    compressed.resize(meshopt_encodeVertexBuffer(compressed.data(), compressed.size(), encoded.data(), count, 8));

    tinygltf::Model model;
    model.buffers.resize(2);
    model.buffers[0].data = compressed;
    model.bufferViews.resize(1);
    model.bufferViews[0].buffer = 1;
    model.bufferViews[0].byteLength = count * 8;
    gltf::MeshoptPlan plan;
    plan.views.push_back(
        {0, 0, 0, compressed.size(), 8, count, gltf::MeshoptMode::Attributes, gltf::MeshoptFilter::Quaternion});
    plan.fallback_buffers = {1};
    gltf::decode_meshopt(model, plan, "q.gltf");
    const tinygltf::BufferView& view = model.bufferViews[0];
    ASSERT_EQ(view.byteOffset, 0u);
    ASSERT_EQ(model.buffers[std::size_t(view.buffer)].data.size(), count * 8);
    for (std::size_t q = 0; q < count; ++q) {
        std::int16_t s[4];
        std::memcpy(s, model.buffers[std::size_t(view.buffer)].data.data() + q * 8, 8);
        // q and −q are the same rotation.
        float same = 0, opposite = 0;
        for (int c = 0; c < 4; ++c) {
            const float x = float(s[c]) / 32767.0f, want = quats[q * 4 + std::size_t(c)];
            same = std::max(same, std::fabs(x - want));
            opposite = std::max(opposite, std::fabs(x + want));
        }
        EXPECT_LE(std::min(same, opposite), 2e-3f) << q;
    }
}

// Broken extension data: one line naming the file, the buffer view and
// what is wrong, before anything is allocated from its claims.
TEST(GltfMeshopt, BrokenExtensionDataIsOneErrorLine) {
    const Grid g = make_grid(5);
    const auto view_ext = [](GltfFile& f, int v) -> nlohmann::json& {
        return f.doc["bufferViews"][std::size_t(v)]["extensions"][Packed::kMeshoptName];
    };
    const struct {
        const char* name;
        std::function<void(GltfFile&)> damage;
        const char* message;
    } cases[] = {
        {"truncated data",
         [&](GltfFile& f) { view_ext(f, 0)["byteLength"] = view_ext(f, 0)["byteLength"].get<int>() / 2; },
         "bufferView 0: EXT_meshopt_compression: the ATTRIBUTES data of"},
        {"truncated indices", [&](GltfFile& f) { view_ext(f, 3)["byteLength"] = 8; }, "the TRIANGLES data of 8 bytes"},
        {"count beyond the view", [&](GltfFile& f) { view_ext(f, 0)["count"] = std::uint64_t{1} << 40; },
         "count 1099511627776 × byteStride 12 is not the bufferView's byteLength"},
        {"huge view from few bytes",
         [&](GltfFile& f) {
             view_ext(f, 0)["count"] = std::uint64_t{1} << 36;
             f.doc["bufferViews"][0]["byteLength"] = (std::uint64_t{1} << 36) * 12;
         },
         "compressed bytes cannot hold"},
        {"bad mode", [&](GltfFile& f) { view_ext(f, 1)["mode"] = "VERTICES"; },
         "bufferView 1: EXT_meshopt_compression: mode 'VERTICES' is not ATTRIBUTES, TRIANGLES or INDICES"},
        {"bad filter", [&](GltfFile& f) { view_ext(f, 1)["filter"] = "LOG"; }, "filter 'LOG' is not NONE"},
        {"octahedral of 12 bytes", [&](GltfFile& f) { view_ext(f, 1)["filter"] = "OCTAHEDRAL"; },
         "OCTAHEDRAL needs a byteStride of 4 or 8"},
        {"filtered indices", [&](GltfFile& f) { view_ext(f, 3)["filter"] = "EXPONENTIAL"; }, "take no filter"},
        {"triangles not in threes",
         [&](GltfFile& f) {
             view_ext(f, 3)["count"] = 4;
             f.doc["bufferViews"][3]["byteLength"] = 16;
         },
         "count divisible by 3"},
        {"stride of 6", [&](GltfFile& f) { view_ext(f, 0)["byteStride"] = 6; }, "differs from the bufferView's 12"},
        {"missing count", [&](GltfFile& f) { view_ext(f, 2).erase("count"); },
         "bufferView 2: EXT_meshopt_compression: count is missing"},
        {"compressed data past its buffer", [&](GltfFile& f) { view_ext(f, 2)["byteOffset"] = 1 << 20; },
         "overrun buffer 0"},
        {"compressed data in the fallback buffer", [&](GltfFile& f) { view_ext(f, 2)["buffer"] = 1; },
         "buffer 1 is a fallback buffer"},
        {"a plain view in the fallback buffer", [&](GltfFile& f) { f.doc["bufferViews"][2].erase("extensions"); },
         "bufferView 2 refers to buffer 1, a fallback buffer without data"},
        {"garbage", [&](GltfFile& f) { f.bin.replace(0, 16, std::string(16, '\x5a')); }, "does not decode"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        auto [plain, packed] = twins(g, "TRIANGLES", 4);
        c.damage(packed.file);
        TempFolder dir;
        const std::filesystem::path path = packed.save(dir, "m.gltf");
        Diagnostics diag;
        try {
            load_gltf(path, diag);
            ADD_FAILURE() << "loaded";
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), path.string());
            EXPECT_NE(e.message().find(c.message), std::string::npos) << e.message();
            EXPECT_EQ(e.message().find('\n'), std::string::npos) << e.message();
        }
    }
}

// Without the extension, a buffer without a uri is named as such (not
// tinygltf's message), and an unsupported required extension is named before
// any buffer check (spec §24).
TEST(GltfMeshopt, BuffersWithoutDataAndRequiredExtensionsAreNamedInOrder) {
    const Grid g = make_grid(4);
    TempFolder dir;
    for (const char* name : {"m.gltf", "m.glb"}) {
        SCOPED_TRACE(name);
        auto [plain, packed] = twins(g, "TRIANGLES", 4);
        packed.file.doc.erase("extensionsUsed");
        packed.file.doc.erase("extensionsRequired");
        const std::filesystem::path path = packed.save(dir, name);
        Diagnostics diag;
        try {
            load_gltf(path, diag);
            ADD_FAILURE() << "loaded";
        } catch (const Error& e) {
            EXPECT_NE(e.message().find("buffer 1 has no uri"), std::string::npos) << e.message();
        }
        packed.file.use_extension("EXT_future_compression", true);
        packed.save(dir, name);
        try {
            load_gltf(path, diag);
            ADD_FAILURE() << "loaded";
        } catch (const Error& e) {
            EXPECT_EQ(e.message(), "requires the unsupported glTF extension EXT_future_compression");
        }
    }
}

}  // namespace
}  // namespace sombra
