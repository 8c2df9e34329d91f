// libFuzzer target: bytes as an OpenVDB file → read_vdb_density (grid "density").
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sombra::fuzz::run_or_abort(sombra::fuzz::Target::Vdb, "vdb", data, size);
    return 0;
}
