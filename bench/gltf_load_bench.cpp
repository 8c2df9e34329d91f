// `sombra-bench load FILE.gltf|.glb`: sombra's glTF loader against
// tinygltf's parse alone (the library it builds on), as the OBJ loader is
// measured against tinyobjloader (load_bench.cpp).
#include <filesystem>
#include <iostream>
#include <optional>
#include <vector>

#include "bench_util.h"
#include "io/gltf/gltf.h"
#include "io/mesh_file.h"
#include "load_bench.h"

namespace sombra::bench {

namespace {

bool skip_image(tinygltf::Image*, int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// tinygltf's own LoadBinaryFromFile / LoadASCIIFromFile with its default
// file access, images skipped (sombra's build has no stb_image in tinygltf).
// Nothing when tinygltf refuses the file: 2.7 built without
// TINYGLTF_ENABLE_DRACO rejects Draco-compressed primitives.
std::optional<std::string> parse_with_tinygltf(const std::string& file) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&skip_image, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool binary = std::filesystem::path(file).extension() == ".glb";
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                           : loader.LoadASCIIFromFile(&model, &err, &warn, file);
    if (ok) return std::nullopt;
    return err.substr(0, err.find('\n'));
}

}  // namespace

void run_gltf_load_bench(const std::string& file, int reps, std::ostream& out) {
    const double megabytes = double(std::filesystem::file_size(file)) * 1e-6;
    std::cerr << "sombra-bench: " << file << ": one untimed load each, then " << reps << " rounds\n";
    Diagnostics diag;
    const std::uint64_t triangles = load_gltf(file, diag).mesh.triangle_count();
    const std::optional<std::string> refused = parse_with_tinygltf(file);

    std::vector<double> full, guarded, plain;
    for (int rep = 0; rep < reps; ++rep) {
        auto start = Clock::now();
        load_gltf(file, diag);
        full.push_back(seconds_since(start));
        start = Clock::now();
        gltf::parse_file(file, diag);
        guarded.push_back(seconds_since(start));
        if (!refused) {
            start = Clock::now();
            parse_with_tinygltf(file);
            plain.push_back(seconds_since(start));
        }
    }
    const double base = refused ? median(guarded) : median(plain);
    Table table;
    table.header = {"loader", "file", "MB", "triangles", "seconds", "time / tinygltf's parse"};
    table.right = {false, false, true, true, true, true};
    const std::string name = std::filesystem::path(file).filename().string();
    table.rows.push_back({"sombra `load_gltf` (guards, parse, accessors or Draco, nodes, mesh)", name,
                          fixed(megabytes, 2), thousands(triangles), seconds(median(full)), ratio(median(full), base)});
    table.rows.push_back({"sombra's guards + tinygltf parse (`gltf::parse_file`)", name, fixed(megabytes, 2), "",
                          seconds(median(guarded)), ratio(median(guarded), base)});
    table.rows.push_back({"tinygltf `LoadBinaryFromFile`/`LoadASCIIFromFile` alone", name, fixed(megabytes, 2), "",
                          refused ? "refused: " + *refused : seconds(median(plain)), refused ? "" : "1.00"});
    out << to_markdown(table);
}

}  // namespace sombra::bench
