// libFuzzer target for the shard files `sombra merge` reads (spec §21) and
// the layers `sombra denoise` reads (§25): they come from other machines.
// An input that starts with 'P' is read as a PFM file instead (read_pfm:
// Python's sombra.read_image), the other float image format sombra reads.
// The input is written as an .exr and read back with read_exr_channels
// (image/image_io.h), as merge reads each part, then taken as the
// denoiser's layers and, when they pass its check and are small, denoised:
// anything may be refused with an Error, nothing may crash, hang or
// allocate past the image limits, and what is read must be consistent.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/image_limits.h"
#include "denoise/denoise.h"
#include "image/image_io.h"

namespace {

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "fuzz_shard: %s\n", what);
    std::abort();
}

// The input written to this process's scratch file with `extension`
// (".exr", ".pfm"), which the readers take by path.
std::filesystem::path written_input(const std::uint8_t* data, std::size_t size, const char* extension) {
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("sombra-fuzz-shard-" + std::to_string(::getpid()) + extension);
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return file;
}

// A PFM file: refused with an Error or read whole, its size within the limits.
void fuzz_pfm(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path file = written_input(data, size, ".pfm");
    try {
        const sombra::PfmImage image = sombra::read_pfm(file);
        if (image.width <= 0 || image.height <= 0 || image.width > sombra::kMaxImageSide ||
            image.height > sombra::kMaxImageSide)
            broken("a PFM size outside the limits was accepted");
        if (image.rgb.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3)
            broken("a PFM image of the wrong length");
    } catch (const sombra::Error&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > 0 && data[0] == 'P') {
        fuzz_pfm(data, size);
        return 0;
    }
    const std::filesystem::path file = written_input(data, size, ".exr");
    try {
        const sombra::ExrChannels exr = sombra::read_exr_channels(file);
        if (exr.width <= 0 || exr.height <= 0 || exr.width > sombra::kMaxImageSide ||
            exr.height > sombra::kMaxImageSide)
            broken("a size outside the limits was accepted");
        if (exr.names.size() != exr.values.size()) broken("names and channels disagree");
        for (const auto& channel : exr.values)
            if (channel.size() != static_cast<std::size_t>(exr.width) * static_cast<std::size_t>(exr.height))
                broken("a channel of the wrong length");
        const sombra::DenoiseLayers layers =
            sombra::denoise_layers_from(exr.names, exr.values, exr.width, exr.height, file.string());
        sombra::check_denoise_layers(layers, file.string());
        // Small images only: the denoiser's time grows with the pixels, not with the file's tricks.
        if (exr.width * exr.height <= 48 * 48) {
            for (const float v : sombra::denoise_image(layers, 1))
                if (!(v >= 0.0f) || v == std::numeric_limits<float>::infinity())
                    broken("the denoiser made a NaN, infinite or negative value");
        }
    } catch (const sombra::Error&) {
        // Refused with a message: what merge prints.
    }
    return 0;
}
