// libFuzzer target: bytes as OBJ text (and MTL text after a "#MTL" line, see
// fuzz_harness.h) → load_obj; and the parser's result the same for any chunking.
#include "fuzz_target.h"
#include "obj_chunking.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sombra::fuzz::run_or_abort(sombra::fuzz::Target::Obj, "obj", data, size);
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::string_view obj = bytes.substr(0, bytes.find(sombra::fuzz::kMtlSeparator));
    const std::string problem = sombra::fuzz::obj_chunking_problem(obj);
    if (!problem.empty()) {
        std::fprintf(stderr, "sombra fuzz_obj: %s\n", problem.c_str());
        std::abort();
    }
    return 0;
}
