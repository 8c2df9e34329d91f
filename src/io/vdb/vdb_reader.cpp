#include "io/vdb/vdb_reader.h"

#include <openvdb/openvdb.h>
#include <cmath>
#include <mutex>
#include <new>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "io/vdb/isolated_read.h"

namespace sombra {

namespace fs = std::filesystem;

namespace {

// OpenVDB's type registry must be filled once per process before a file is read.
void initialize_openvdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

// The grid names the file holds, for a message: "'a', 'b'" (at most eight).
std::string grid_names(openvdb::io::File& file) {
    std::string names;
    int count = 0;
    for (auto it = file.beginName(); it != file.endName(); ++it, ++count) {
        if (count == 8) return names + ", …";
        names += (names.empty() ? "'" : ", '") + it.gridName() + "'";
    }
    return names.empty() ? "none" : names;
}

// A metadata value the file claims, when it has one of that type.
template <class T>
bool claimed(const openvdb::GridBase& grid, const char* name, T& value) {
    const auto meta = grid.getMetadata<openvdb::TypedMetadata<T>>(name);
    if (!meta) return false;
    value = meta->value();
    return true;
}

// The number of voxels of a box of `size` voxels a side, padded by one on every side.
std::uint64_t padded_voxels(const openvdb::Coord& size) {
    std::uint64_t n = 1;
    for (int a = 0; a < 3; ++a) {
        const std::int64_t side = static_cast<std::int64_t>(size[a]) + 2;
        if (side <= 0 || static_cast<std::uint64_t>(side) > kMaxDenseVoxels) return kMaxDenseVoxels + 1;
        n *= static_cast<std::uint64_t>(side);
        if (n > kMaxDenseVoxels) return kMaxDenseVoxels + 1;
    }
    return n;
}

std::string too_large(const openvdb::Coord& size) {
    return "the grid's active voxels span " + std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " +
           std::to_string(size[2]) + ", more than sombra reads (" + std::to_string(kMaxDenseVoxels) +
           " voxels once dense)";
}

Transform affine_transform(const openvdb::math::Transform& t, const std::string& where) {
    if (!t.isLinear()) throw Error(where, "the grid's transform is not affine (a frustum): not supported");
    const openvdb::math::Mat4d m = t.baseMap()->getAffineMap()->getMat4();
    // OpenVDB multiplies row vectors (world = index · M); sombra's matrices take column vectors.
    Transform out;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            const double v = m(c, r);
            if (!std::isfinite(v)) throw Error(where, "the grid's transform is not finite");
            out.m[static_cast<std::size_t>(r) * 4 + static_cast<std::size_t>(c)] = static_cast<float>(v);
        }
    return out;
}

// The grid read and made dense in this process (the child, read_vdb_density).
DensityGrid read_here(const fs::path& path, const std::string& grid_name) {
    const std::string name = path.string();
    initialize_openvdb();

    DensityGrid out;
    openvdb::FloatGrid::Ptr grid;
    try {
        openvdb::io::File file(name);
        file.open(false);  // read what is asked for now, not lazily while rendering
        if (!file.hasGrid(grid_name))
            throw Error(name, "no grid '" + grid_name + "' (the file has " + grid_names(file) + ")");
        const openvdb::GridBase::Ptr meta = file.readGridMetadata(grid_name);
        if (meta->valueType() != "float")
            throw Error(name, "grid '" + grid_name + "' holds " + meta->valueType() + " values, not float densities");
        // What the file says of the grid's size, checked before its tree is read.
        openvdb::Vec3i lo, hi;
        if (claimed(*meta, openvdb::GridBase::META_FILE_BBOX_MIN, lo) &&
            claimed(*meta, openvdb::GridBase::META_FILE_BBOX_MAX, hi)) {
            const openvdb::Coord claimed_size(hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1);
            if (padded_voxels(claimed_size) > kMaxDenseVoxels) throw Error(name, too_large(claimed_size));
        }
        grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(grid_name));
        file.close();
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw Error(name, "not a readable OpenVDB file (it asks for more memory than sombra lets it have)");
    } catch (const std::exception& e) {
        std::string what = e.what();
        if (what.size() > 200) what.resize(200);
        throw Error(name, "not a readable OpenVDB file (" + what + ")");
    }
    if (!grid) throw Error(name, "grid '" + grid_name + "' is not a float grid");

    out.index_to_world = affine_transform(grid->transform(), name);
    // The active box, walked in one thread (OpenVDB's own evaluation may use
    // TBB, which a forked process must not).
    openvdb::CoordBBox box;
    for (auto it = grid->cbeginValueOn(); it; ++it)
        if (it.isVoxelValue())
            box.expand(it.getCoord());
        else
            box.expand(it.getBoundingBox());
    const openvdb::Coord lo = box.empty() ? openvdb::Coord(0) : box.min();
    const openvdb::Coord extent = box.empty() ? openvdb::Coord(0) : box.dim();
    if (padded_voxels(extent) > kMaxDenseVoxels) throw Error(name, too_large(extent));
    for (int a = 0; a < 3; ++a) {
        out.dims[static_cast<std::size_t>(a)] = extent[a] + 2;
        out.origin[static_cast<std::size_t>(a)] = lo[a] - 1;
    }
    out.values.assign(padded_voxels(extent), 0.0f);
    const auto nx = static_cast<std::size_t>(out.dims[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(out.dims[1]);
    auto put = [&](const openvdb::Coord& c, float value) {
        if (!std::isfinite(value) || value < 0.0f) {
            std::ostringstream message;
            message << "voxel (" << c[0] << ", " << c[1] << ", " << c[2] << ") of grid '" << grid_name << "' holds "
                    << value << ": a density must be finite and >= 0";
            throw Error(name, message.str());
        }
        out.values[static_cast<std::size_t>(c[0] - out.origin[0]) +
                   static_cast<std::size_t>(c[1] - out.origin[1]) * nx +
                   static_cast<std::size_t>(c[2] - out.origin[2]) * nxy] = value;
    };
    for (auto it = grid->cbeginValueOn(); it; ++it) {
        if (it.isVoxelValue()) {
            put(it.getCoord(), *it);
            continue;
        }
        // An active tile: every voxel of its box holds its value.
        const openvdb::CoordBBox tile = it.getBoundingBox();
        for (auto c = tile.begin(); c; ++c) put(*c, *it);
    }
    // The dense box's index coordinates, then the file's transform.
    out.index_to_world =
        compose(make_translate(Vec3{static_cast<float>(out.origin[0]), static_cast<float>(out.origin[1]),
                                    static_cast<float>(out.origin[2])}),
                out.index_to_world);
    return out;
}

}  // namespace

DensityGrid read_vdb_density(const fs::path& path, const std::string& grid_name) {
    const std::string name = path.string();
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw Error(name, "cannot open OpenVDB file: no such file");
    if (!fs::is_regular_file(status)) throw Error(name, "cannot open OpenVDB file: not a regular file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > kMaxVdbFileBytes)
        throw Error(name, "OpenVDB file is larger than " + std::to_string(kMaxVdbFileBytes >> 30) + " GiB");
    DensityGrid out = read_isolated(name, ec ? 0 : size, [&] { return read_here(path, grid_name); });
    out.source = path.filename().string() + ": " + grid_name;
    build_majorants(out);
    return out;
}

}  // namespace sombra
