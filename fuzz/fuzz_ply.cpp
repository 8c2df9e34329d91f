// libFuzzer target: bytes as PLY (ascii or binary) → load_ply.
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sombra::fuzz::run_or_abort(sombra::fuzz::Target::Ply, "ply", data, size);
    return 0;
}
