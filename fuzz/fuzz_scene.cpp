// libFuzzer target: bytes as scene JSON → load_scene_file, objects can name m.obj (with m.mtl) or m.ply beside it.
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sombra::fuzz::run_or_abort(sombra::fuzz::Target::Scene, "scene", data, size);
    return 0;
}
