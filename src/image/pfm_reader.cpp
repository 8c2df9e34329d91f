// Reading a portable float map back (Python's read_image): the file is
// untrusted, so its header's size must match its bytes before any
// allocation follows the header's claims.
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_limits.h"
#include "image/image_io.h"

namespace sombra {

namespace {

float load_float(const unsigned char* p, bool little_endian) {
    std::uint32_t bits = 0;
    for (int byte = 0; byte < 4; ++byte) bits |= std::uint32_t{p[little_endian ? byte : 3 - byte]} << (8 * byte);
    return std::bit_cast<float>(bits);
}

}  // namespace

PfmImage read_pfm(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw Error(name, "cannot open: " + ec.message());
    // The largest image sombra reads, in float RGB, with room for the header.
    if (size > static_cast<std::uintmax_t>(kMaxPixels) * 12 + 64) throw Error(name, "too large for a PFM file");
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw Error(name, "cannot read the file");
    std::istringstream header(bytes.substr(0, 128));
    std::string magic;
    long long width = 0, height = 0;
    double scale = 0;
    header >> magic >> width >> height >> scale;
    if (!header || (magic != "PF" && magic != "Pf") || !std::isfinite(scale) || scale == 0)
        throw Error(name, "not a PFM file (expected 'PF' or 'Pf', the width and height, and a non-zero scale)");
    if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxPixels)
        throw Error(name, "a PFM image of " + std::to_string(width) + "x" + std::to_string(height) +
                              " pixels is out of range (1 to " + std::to_string(kMaxImageSide) + " a side)");
    const std::size_t channels = magic == "PF" ? 3 : 1;
    const auto data = static_cast<std::size_t>(header.tellg()) + 1;  // one whitespace byte ends the header
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (bytes.size() != data + pixels * channels * 4)
        throw Error(name, "holds " + std::to_string(bytes.size()) + " bytes, not the " +
                              std::to_string(data + pixels * channels * 4) + " its header says");
    PfmImage image{static_cast<int>(width), static_cast<int>(height), std::vector<float>(pixels * 3)};
    const auto* floats = reinterpret_cast<const unsigned char*>(bytes.data() + data);
    for (std::size_t stored = 0; stored < static_cast<std::size_t>(height); ++stored) {
        const std::size_t row = static_cast<std::size_t>(height) - 1 - stored;  // PFM rows run bottom to top
        for (std::size_t x = 0; x < static_cast<std::size_t>(width); ++x)
            for (std::size_t c = 0; c < 3; ++c) {
                const std::size_t from = ((stored * static_cast<std::size_t>(width) + x) * channels + c % channels) * 4;
                image.rgb[(row * static_cast<std::size_t>(width) + x) * 3 + c] = load_float(floats + from, scale < 0);
            }
    }
    return image;
}

}  // namespace sombra
