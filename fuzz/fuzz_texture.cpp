// libFuzzer target: bytes as an image file → read_texture_file (PNG, JPEG, TGA, BMP by content; .hdr, .exr).
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    sombra::fuzz::run_or_abort(sombra::fuzz::Target::Texture, "texture", data, size);
    return 0;
}
