// libFuzzer target: bytes as glTF 2.0 (JSON .gltf, or .glb when they start
// with "glTF") → load_gltf, tinygltf and Draco included.
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sombra::fuzz::run_or_abort(sombra::fuzz::Target::Gltf, "gltf", data, size);
    return 0;
}
