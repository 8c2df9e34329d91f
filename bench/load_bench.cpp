#include "load_bench.h"

#include <tiny_obj_loader.h>

#include <filesystem>
#include <iostream>
#include <vector>

#include "bench_util.h"
#include "core/error.h"
#include "io/mesh_file.h"

namespace sombra::bench {

namespace {

// Triangles sombra's loader produced.
std::uint64_t load_with_sombra(const std::string& file) {
    Diagnostics diag;
    return load_obj(file, diag).mesh.triangle_count();
}

// Triangles a fan triangulation of tinyobjloader's faces would give.
std::uint64_t load_with_tinyobj(const std::string& file) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    const std::string folder = std::filesystem::path(file).parent_path().string() + "/";
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, file.c_str(), folder.c_str(),
                          /*triangulate=*/false)) {
        throw Error(file, "tinyobjloader failed: " + err);
    }
    std::uint64_t triangles = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        for (const unsigned int corners : shape.mesh.num_face_vertices) triangles += corners >= 3 ? corners - 2 : 0;
    }
    return triangles;
}

}  // namespace

void run_load_bench(const std::string& file, int reps, std::ostream& out) {
    const double megabytes = double(std::filesystem::file_size(file)) * 1e-6;
    std::cerr << "sombra-bench: " << file << ": one untimed load each, then " << reps << " rounds\n";
    const std::uint64_t sombra_triangles = load_with_sombra(file);
    const std::uint64_t tinyobj_triangles = load_with_tinyobj(file);
    if (sombra_triangles != tinyobj_triangles) {
        throw Error(file, "sombra reads " + thousands(sombra_triangles) + " triangles, tinyobjloader's faces give " +
                              thousands(tinyobj_triangles) + ": not timing loaders that disagree");
    }

    std::vector<double> sombra_times, tinyobj_times;
    for (int rep = 0; rep < reps; ++rep) {
        for (int i = 0; i < 2; ++i) {
            const bool sombra_turn = (i == 0) == (rep % 2 == 0);
            const auto start = Clock::now();
            if (sombra_turn) {
                load_with_sombra(file);
                sombra_times.push_back(seconds_since(start));
            } else {
                load_with_tinyobj(file);
                tinyobj_times.push_back(seconds_since(start));
            }
        }
    }
    const double sombra_s = median(sombra_times), tinyobj_s = median(tinyobj_times);

    Table table;
    table.header = {"loader", "file", "MB", "triangles", "seconds", "MB/s", "time / tinyobjloader's"};
    table.right = {false, false, true, true, true, true, true};
    const std::string name = std::filesystem::path(file).filename().string();
    table.rows.push_back({"sombra `load_obj` (validates, triangulates, builds the mesh)", name, fixed(megabytes, 1),
                          thousands(sombra_triangles), seconds(sombra_s), fixed(megabytes / sombra_s, 0),
                          ratio(sombra_s, tinyobj_s)});
    table.rows.push_back({"tinyobjloader `LoadObj`, triangulate = false (parses only)", name, fixed(megabytes, 1),
                          thousands(tinyobj_triangles), seconds(tinyobj_s), fixed(megabytes / tinyobj_s, 0), "1.00"});
    out << to_markdown(table);
}

}  // namespace sombra::bench
