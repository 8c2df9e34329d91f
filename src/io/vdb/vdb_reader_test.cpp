// OpenVDB files as grid media's densities: the voxels and transform read
// back as written, and every bad file refused in one line.
#include "io/vdb/vdb_reader.h"

#include <gtest/gtest.h>

#include <openvdb/openvdb.h>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace sombra {
namespace {

namespace fs = std::filesystem;

class VdbReader : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        openvdb::initialize();
        dir = fs::temp_directory_path() / ("sombra_vdb_" + std::to_string(::getpid()));
        fs::create_directories(dir);
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    static fs::path write(const std::string& file, const openvdb::GridPtrVec& grids) {
        fs::path path = dir / file;
        openvdb::io::File(path.string()).write(grids);
        return path;
    }
    // The message of reading grid `grid` of `path` ("" when it reads).
    static std::string error_of(const fs::path& path, const std::string& grid) {
        try {
            read_vdb_density(path, grid);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }
    static inline fs::path dir;
};

TEST_F(VdbReader, ReadsActiveVoxelsTilesAndTheTransform) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
    grid->transform().postTranslate(openvdb::Vec3d(1, 2, 3));
    auto acc = grid->getAccessor();
    acc.setValue(openvdb::Coord(2, 3, 4), 0.75f);
    acc.setValue(openvdb::Coord(5, 3, 4), 2.0f);
    acc.setValueOff(openvdb::Coord(4, 3, 4), 9.0f);  // inactive: reads as 0
    const DensityGrid d = read_vdb_density(write("two.vdb", {grid}), "density");
    EXPECT_EQ(d.dims, (std::array<int, 3>{4 + 2, 1 + 2, 1 + 2}));
    EXPECT_EQ(d.origin, (std::array<int, 3>{1, 2, 3}));
    // Dense (1, 1, 1) is index (2, 3, 4); (4, 1, 1) is (5, 3, 4); (3, 1, 1) the inactive one.
    EXPECT_EQ(density_at(d, {1, 1, 1}), 0.75f);
    EXPECT_EQ(density_at(d, {4, 1, 1}), 2.0f);
    EXPECT_EQ(density_at(d, {3, 1, 1}), 0.0f);
    EXPECT_FLOAT_EQ(density_at(d, {3.5f, 1, 1}), 1.0f);
    EXPECT_EQ(d.max_value, 2.0f);
    // Dense (1, 1, 1) → index (2, 3, 4) → world 0.5·(2, 3, 4) + (1, 2, 3).
    const Vec3 w = transform_point(d.index_to_world, {1, 1, 1});
    EXPECT_FLOAT_EQ(w.x, 2.0f);
    EXPECT_FLOAT_EQ(w.y, 3.5f);
    EXPECT_FLOAT_EQ(w.z, 5.0f);
    EXPECT_EQ(d.source, "two.vdb: density");
}

TEST_F(VdbReader, AnActiveTileFillsItsBox) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->tree().addTile(1, openvdb::Coord(0, 0, 0), 0.5f, true);  // an 8³ tile at level 1
    const DensityGrid d = read_vdb_density(write("tile.vdb", {grid}), "density");
    EXPECT_EQ(d.dims, (std::array<int, 3>{10, 10, 10}));
    EXPECT_EQ(density_at(d, {4.5f, 7.9f, 1.0f}), 0.5f);
}

TEST_F(VdbReader, BadFilesAreOneLineErrors) {
    auto vec = openvdb::Vec3SGrid::create();
    vec->setName("velocity");
    auto negative = openvdb::FloatGrid::create(0.0f);
    negative->setName("density");
    negative->getAccessor().setValue(openvdb::Coord(1, 2, 3), -0.5f);
    const fs::path two = write("vec.vdb", {vec, negative});
    const std::string name = two.string();
    EXPECT_EQ(error_of(two, "smoke"), name + ": no grid 'smoke' (the file has 'density', 'velocity')");
    EXPECT_EQ(error_of(two, "velocity"), name + ": grid 'velocity' holds vec3s values, not float densities");
    EXPECT_EQ(error_of(two, "density"),
              name + ": voxel (1, 2, 3) of grid 'density' holds -0.5: a density must be finite and >= 0");
    EXPECT_EQ(error_of(dir / "missing.vdb", "density"),
              (dir / "missing.vdb").string() + ": cannot open OpenVDB file: no such file");
    EXPECT_EQ(error_of(dir, "density"), dir.string() + ": cannot open OpenVDB file: not a regular file");
    const fs::path junk = dir / "junk.vdb";
    std::ofstream(junk) << "this is not a VDB file at all";
    EXPECT_EQ(error_of(junk, "density").rfind(junk.string() + ": not a readable OpenVDB file (", 0), 0u);
}

TEST_F(VdbReader, AGridTooLargeOnceDenseIsRefusedBeforeItIsRead) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->getAccessor().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    grid->getAccessor().setValue(openvdb::Coord(2000, 2000, 2000), 1.0f);
    const fs::path path = write("far.vdb", {grid});
    EXPECT_NE(
        error_of(path, "density").find("the grid's active voxels span 2001 x 2001 x 2001, more than sombra reads"),
        std::string::npos);
}

TEST_F(VdbReader, TheSharedCloud) {
    const fs::path cloud = fs::path(SOMBRA_SHARED_DIR) / "models/vdb/cloud.vdb";
    if (!fs::exists(cloud)) GTEST_SKIP() << "needs ../shared/models/vdb/cloud.vdb";
    const DensityGrid d = read_vdb_density(cloud, "density");
    EXPECT_EQ(d.dims, (std::array<int, 3>{64, 61, 64}));  // active [1, 4, 1] … [62, 62, 62], padded
    EXPECT_GT(d.max_value, 0.5f);
    EXPECT_LE(d.max_value, 1.0f);
    // Voxel (i, j, k) is centred at −1 + (i + 0.5)/32.
    const Vec3 w = transform_point(d.index_to_world, {1, 1, 1});  // index (1, 4, 1)
    EXPECT_FLOAT_EQ(w.x, -1.0f + 1.5f / 32.0f);
    EXPECT_FLOAT_EQ(w.y, -1.0f + 4.5f / 32.0f);
}

}  // namespace
}  // namespace sombra
