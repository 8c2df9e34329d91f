// libFuzzer target: bytes as OBJ text (and MTL text after a "#MTL" line, see fuzz_harness.h) → load_obj.
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sombra::fuzz::run_or_abort(sombra::fuzz::Target::Obj, "obj", data, size);
    return 0;
}
