// Test helper: writing small PNG (8 or 16 bit, through libpng), TGA, BMP and
// JPEG (through stb_image_write) files whose every value the test chooses,
// for the texture, scene-file, render and command-line tests.
#pragma once

#include <png.h>
#include <stb_image_write.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace sombra::testing {

// Writes a PNG of width × height pixels of `channels` (1 grey, 2 grey +
// alpha, 3 RGB, 4 RGBA) values each, `values` row by row from the top, at
// 8 or 16 bits per value.
inline void write_png_file(const std::filesystem::path& file, int width, int height, int channels, int bits,
                           const std::vector<std::uint16_t>& values) {
    std::FILE* out = std::fopen(file.c_str(), "wb");
    if (!out) throw std::runtime_error("cannot write " + file.string());
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        std::fclose(out);
        throw std::runtime_error("libpng failed writing " + file.string());
    }
    png_init_io(png, out);
    const int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGBA};
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bits,
                 types[channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    const std::size_t row_values = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
    std::vector<unsigned char> row(row_values * static_cast<std::size_t>(bits / 8));
    for (int y = 0; y < height; ++y) {
        for (std::size_t i = 0; i < row_values; ++i) {
            const std::uint16_t v = values[static_cast<std::size_t>(y) * row_values + i];
            if (bits == 16) {  // big endian, as PNG stores it
                row[2 * i] = static_cast<unsigned char>(v >> 8);
                row[2 * i + 1] = static_cast<unsigned char>(v & 0xff);
            } else {
                row[i] = static_cast<unsigned char>(v);
            }
        }
        png_write_row(png, row.data());
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fclose(out) != 0) throw std::runtime_error("cannot write " + file.string());
}

// 8-bit images through stb_image_write: "tga", "bmp" or "jpg" (quality 100).
inline void write_stb_file(const std::filesystem::path& file, const std::string& format, int width, int height,
                           int channels, const std::vector<unsigned char>& values) {
    int ok = 0;
    if (format == "tga")
        ok = stbi_write_tga(file.c_str(), width, height, channels, values.data());
    else if (format == "bmp")
        ok = stbi_write_bmp(file.c_str(), width, height, channels, values.data());
    else if (format == "jpg")
        ok = stbi_write_jpg(file.c_str(), width, height, channels, values.data(), 100);
    if (!ok) throw std::runtime_error("cannot write " + file.string());
}

inline std::vector<unsigned char> read_file_bytes(const std::filesystem::path& file) {
    std::vector<unsigned char> bytes(std::filesystem::file_size(file));
    std::FILE* in = std::fopen(file.c_str(), "rb");
    if (!in) throw std::runtime_error("cannot read " + file.string());
    const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), in);
    std::fclose(in);
    if (got != bytes.size()) throw std::runtime_error("cannot read " + file.string());
    return bytes;
}

// A PNG's first bytes, up to and including an IHDR chunk claiming width ×
// height RGBA pixels at 8 bits (stb does not check chunk CRCs: zeros), then
// an empty IDAT and IEND: what a hostile file's header may claim.
inline std::string png_claiming(std::uint32_t width, std::uint32_t height) {
    std::string bytes = "\x89PNG\r\n\x1a\n";
    const auto be32 = [&](std::uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((v >> shift) & 0xff);
    };
    be32(13);
    bytes += "IHDR";
    be32(width);
    be32(height);
    bytes += std::string("\x08\x06\x00\x00\x00", 5);
    be32(0);
    be32(0);
    bytes += "IDAT";
    be32(0);
    be32(0);
    bytes += "IEND";
    be32(0);
    return bytes;
}

}  // namespace sombra::testing
