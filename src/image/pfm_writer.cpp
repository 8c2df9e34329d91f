#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "image/writers.h"

namespace sombra {

namespace {

// PFM with scale -1.0 stores little-endian floats whatever the host.
void store_little_endian(float value, unsigned char* out) {
    std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
    for (int byte = 0; byte < 4; ++byte) {
        out[byte] = static_cast<unsigned char>(bits & 0xffu);
        bits >>= 8;
    }
}

void write_all(std::FILE* out, const void* data, std::size_t size) {
    if (std::fwrite(data, 1, size, out) != size) throw std::system_error(errno, std::generic_category());
}

}  // namespace

void write_pfm(const std::filesystem::path& file, ImageView image) {
    const auto width = static_cast<std::size_t>(image.width);
    const auto height = static_cast<std::size_t>(image.height);
    OutputFile out = open_for_writing(file);

    const std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
    write_all(out.get(), header.data(), header.size());

    std::vector<unsigned char> row(width * 3 * sizeof(float));
    for (std::size_t stored = 0; stored < height; ++stored) {
        const std::size_t j = height - 1 - stored;  // PFM rows run bottom to top
        for (std::size_t i = 0; i < width; ++i) {
            const std::size_t pixel = j * width + i;
            const bool finite = pixel_is_finite(image.rgb, pixel);
            for (std::size_t c = 0; c < 3; ++c)
                store_little_endian(finite ? image.rgb[3 * pixel + c] : 0.0f, &row[(3 * i + c) * sizeof(float)]);
        }
        write_all(out.get(), row.data(), row.size());
    }
    finish_writing(std::move(out));
}

}  // namespace sombra
