// Replays every reproducer the fuzzers found (fuzz/regressions/TARGET/)
// through the same harness the fuzz targets use: each must load or end in
// sombra::Error, nothing else, and what loads must hold the invariants the
// renderer relies on. tools/fuzz.sh says how a new reproducer gets here.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "../../fuzz/fuzz_harness.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;

const fs::path kRegressions = fs::path(SOMBRA_SOURCE_DIR) / "fuzz" / "regressions";

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The reproducers of one target, sorted so failures read the same every run.
std::vector<fs::path> reproducers(const char* target) {
    std::vector<fs::path> files;
    if (!fs::is_directory(kRegressions / target)) return files;  // git keeps no empty folder
    for (const fs::directory_entry& entry : fs::directory_iterator(kRegressions / target)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

class FuzzRegression : public ::testing::Test {
protected:
    void SetUp() override {
        folder = fs::temp_directory_path() / ("sombra_fuzz_regression_" + std::to_string(::getpid()));
        fs::create_directories(folder);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(folder, ec);
    }

    // Replays every reproducer of `target`; returns how many there were.
    std::size_t replay_all(fuzz::Target target, const char* name) {
        const std::vector<fs::path> files = reproducers(name);
        for (const fs::path& file : files) {
            SCOPED_TRACE(file.string());
            std::string problem;
            EXPECT_NO_THROW(problem = fuzz::run_input(target, read_bytes(file), folder));
            EXPECT_EQ(problem, "");
        }
        return files.size();
    }

    // What the Error thrown by `load` on reproducer `name` in fuzz/regressions/
    // `subfolder`, staged as the fuzzer saw it, says; nullopt when it loads.
    template <class Load>
    std::optional<std::string> refusal(fuzz::Target target, const char* subfolder, const char* name, Load load) {
        const fs::path path = fuzz::stage_input(target, read_bytes(kRegressions / subfolder / name), folder);
        try {
            load(path);
        } catch (const Error& e) {
            return e.message();
        }
        return std::nullopt;
    }

    fs::path folder;
};

TEST_F(FuzzRegression, EveryReproducerLoadsOrFailsCleanly) {
    const std::size_t replayed = replay_all(fuzz::Target::Obj, "obj") + replay_all(fuzz::Target::Ply, "ply") +
                                 replay_all(fuzz::Target::Scene, "scene") +
                                 replay_all(fuzz::Target::Texture, "texture") + replay_all(fuzz::Target::Gltf, "gltf") +
                                 replay_all(fuzz::Target::Vdb, "vdb");
    EXPECT_GE(replayed, 2u);  // at least those tested one by one below
}

// The hand-written seeds of the version-2 keys (fuzz/seeds/scene) load
// through the harness and pass its checks.
TEST_F(FuzzRegression, SceneSeedsLoad) {
    const fs::path seeds = fs::path(SOMBRA_SOURCE_DIR) / "fuzz" / "seeds" / "scene";
    std::size_t count = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(seeds)) {
        SCOPED_TRACE(entry.path().string());
        std::string problem = "threw";
        EXPECT_NO_THROW(problem = fuzz::run_input(fuzz::Target::Scene, read_bytes(entry.path()), folder));
        EXPECT_EQ(problem, "");
        // And they load, not merely fail cleanly.
        Diagnostics diag;
        const fs::path staged = fuzz::stage_input(fuzz::Target::Scene, read_bytes(entry.path()), folder);
        try {
            load_scene_file(staged, diag);
        } catch (const Error& e) {
            ADD_FAILURE() << e.what();
        }
        ++count;
    }
    EXPECT_GE(count, 4u);
}

// fuzz_texture's seeds (fuzz/seeds/texture: every format and layout) decode
// through the harness and pass its checks, and the harness sees a bad texel.
TEST_F(FuzzRegression, TextureSeedsDecode) {
    const fs::path seeds = fs::path(SOMBRA_SOURCE_DIR) / "fuzz" / "seeds" / "texture";
    std::size_t count = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(seeds)) {
        SCOPED_TRACE(entry.path().string());
        const std::string bytes = read_bytes(entry.path());
        std::string problem = "threw";
        EXPECT_NO_THROW(problem = fuzz::run_input(fuzz::Target::Texture, bytes, folder));
        EXPECT_EQ(problem, "");
        try {
            const Texture t =
                read_texture_file(fuzz::stage_input(fuzz::Target::Texture, bytes, folder), TextureEncoding::Color);
            EXPECT_GT(t.texels.size(), 0u);
        } catch (const Error& e) {
            ADD_FAILURE() << e.what();
        }
        ++count;
    }
    EXPECT_GE(count, 18u);
    Texture t;
    t.width = t.height = t.channels = 1;
    t.texels = {1.5f};
    EXPECT_EQ(fuzz::texture_problem(t, false), "");
    EXPECT_EQ(fuzz::texture_problem(t, true), "texel out of range");
}

// The harness itself: a good input loads and passes the checks, and a broken
// invariant is reported (so the replays above can fail).
TEST_F(FuzzRegression, HarnessLoadsAGoodInputAndSeesABrokenOne) {
    const std::string quad = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl a\nf 1 2 3 4\n";
    const fs::path path = fuzz::stage_input(fuzz::Target::Obj, quad + "\n#MTL\nnewmtl a\nKd 0.5 0.25 1\n", folder);
    Diagnostics diag;
    LoadedMesh loaded = load_obj(path, diag);
    ASSERT_EQ(loaded.mesh.triangles.size(), 2u);
    ASSERT_EQ(loaded.materials.size(), 1u);
    EXPECT_FLOAT_EQ(loaded.materials[0].kd.y, 0.25f);  // the MTL part reached the loader as m.mtl
    EXPECT_EQ(fuzz::loaded_mesh_problem(loaded), "");

    loaded.mesh.triangles[1][2] = 4;
    EXPECT_EQ(fuzz::loaded_mesh_problem(loaded), "triangle index out of range");
    loaded.mesh.triangles[1][2] = 3;
    loaded.materials[0].kd.x = 1.5f;
    EXPECT_NE(fuzz::loaded_mesh_problem(loaded), "");
}

// fuzz_scene's fixed meshes load, so that the fuzzer's scenes reach them.
TEST_F(FuzzRegression, HarnessSceneMeshesLoad) {
    const std::string scene = R"({"camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]},
        "objects": [{"file": "m.obj"}, {"file": "m.ply", "transform": [{"translate": [2, 0, 0]}]}]})";
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(fuzz::stage_input(fuzz::Target::Scene, scene, folder), diag);
    EXPECT_EQ(loaded.scene.geometry.triangles.size(), 3u);  // the OBJ quad and the PLY triangle
    ASSERT_FALSE(loaded.scene.materials.empty());
    EXPECT_EQ(loaded.scene.materials[0].name, "red");
    EXPECT_EQ(fuzz::scene_problem(loaded), "");
    EXPECT_TRUE(diag.warnings.empty());
}

// fuzz_texture found these in Debian's stb_image, which decoded JPEGs until
// then: a Huffman table whose 16 code counts add up to more than 256 made it
// write past its tables; then the same behind 0xff fill bytes before the
// start-of-image marker; then a table cut short by the file's end, whose
// missing counts it read as zeros; then a scan using tables the file never
// defines, read from uninitialised memory (UBSan: a shift by 32). libjpeg-turbo
// decodes JPEGs now: it refuses the first three and reads the last with the
// standard tables (JpegTexture.ScanWithoutHuffmanTablesUsesTheStandardOnes).
TEST_F(FuzzRegression, JpegHuffmanTablesStbMisreadAreRefusedOrStandard) {
    const std::pair<const char*, const char*> cases[] = {
        {"jpeg-huffman-counts-over-256.jpg", "cannot decode as JPEG: Bogus Huffman table definition"},
        {"jpeg-huffman-overflow-after-fill-bytes.jpg", "cannot decode as JPEG: Bogus Huffman table definition"},
        {"jpeg-huffman-counts-cut-short-at-the-end.jpg", "JPEG file is truncated"},
    };
    for (const auto& [name, expected] : cases) {
        SCOPED_TRACE(name);
        const std::optional<std::string> message =
            refusal(fuzz::Target::Texture, "texture", name,
                    [](const fs::path& p) { read_texture_file(p, TextureEncoding::Color); });
        ASSERT_TRUE(message) << "decoded a JPEG with a bad Huffman table";
        EXPECT_NE(message->find(expected), std::string::npos) << *message;
    }
    const std::optional<std::string> message =
        refusal(fuzz::Target::Texture, "texture", "ubsan-jpeg-scan-without-huffman-tables.jpg",
                [](const fs::path& p) { EXPECT_EQ(read_texture_file(p, TextureEncoding::Color).width, 64); });
    EXPECT_FALSE(message) << *message;
}

// fuzz_ply found it: a face count of 2^32 - 1 was reserved for (tens of GB)
// before it was checked against the bytes left in the file.
TEST_F(FuzzRegression, PlyFaceCountCheckedBeforeReserving) {
    Diagnostics diag;
    const std::optional<std::string> message =
        refusal(fuzz::Target::Ply, "ply", "oom-face-count-reserved-before-check.ply",
                [&](const fs::path& p) { load_ply(p, diag); });
    ASSERT_TRUE(message) << "loaded a file claiming 4294967295 faces";
    EXPECT_NE(message->find("element 'face' claims 4294967295 entries"), std::string::npos) << *message;
}

// fuzz_gltf found it: an EXT_mesh_gpu_instancing SCALE of (1, 512,
// 1.8e-40), no component zero, gives an instance transform with no inverse
// in float. The scene builder refused it, but only after load_gltf had
// handed it on; the loader now refuses it itself, naming the instance.
TEST_F(FuzzRegression, GltfInstanceWithoutAFloatInverseIsRefused) {
    Diagnostics diag;
    const std::optional<std::string> message =
        refusal(fuzz::Target::Gltf, "gltf", "singular-instance-from-a-denormal-instancing-scale.gltf",
                [&](const fs::path& p) { load_gltf(p, diag); });
    ASSERT_TRUE(message) << "loaded an instance whose transform has no inverse";
    EXPECT_EQ(*message, "node 2: instance 1: the transform is not invertible");
}

// fuzz_obj found it when tinyobjloader still read the geometry: it converted
// a `vw` (skin weight) joint id of 1e38 to int, undefined behaviour. sombra's
// own parser ignores `vw` lines; they must still load.
TEST_F(FuzzRegression, ObjWithHugeSkinWeightJointLoads) {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 1e38 0.5 nan 1\nf 1 2 3\n";
    const fs::path path = fuzz::stage_input(fuzz::Target::Obj, obj, folder);
    Diagnostics diag;
    const LoadedMesh loaded = load_obj(path, diag);
    EXPECT_EQ(loaded.mesh.triangles.size(), 1u);
    EXPECT_EQ(fuzz::loaded_mesh_problem(loaded), "");
}

}  // namespace
}  // namespace sombra
