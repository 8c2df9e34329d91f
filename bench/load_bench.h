// `sombra-bench load`: sombra's OBJ loader against plain tinyobjloader.
#pragma once

#include <ostream>
#include <string>

namespace sombra::bench {

// Loads `obj_file` with sombra's load_obj and with tinyobjloader's LoadObj
// (triangulate = false: parsing only, what sombra builds on), after one
// untimed load each (the file then sits in the page cache), `reps` rounds in
// alternating order, and writes a Markdown table of medians to `out`. Throws
// Error when either loader fails.
void run_load_bench(const std::string& obj_file, int reps, std::ostream& out);

// The same for a .gltf or .glb file: sombra's load_gltf, its guarded parse
// alone, and tinygltf's plain LoadBinaryFromFile / LoadASCIIFromFile (when
// tinygltf accepts the file: not with Draco), medians of `reps` rounds.
void run_gltf_load_bench(const std::string& file, int reps, std::ostream& out);

}  // namespace sombra::bench
