#include <png.h>
#include <zlib.h>

#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "image/atomic_file.h"
#include "image/display_transform.h"
#include "image/writers.h"

namespace sombra {

std::uint8_t encode_srgb8(float linear) {
    if (!(linear > 0.0f)) return 0;  // also NaN
    if (linear >= 1.0f) return 255;
    // The exact piecewise sRGB OETF (IEC 61966-2-1), in double so that the
    // rounding to 8 bits is decided by the formula, not by float error.
    const double v = linear;
    const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(encoded * 255.0));
}

namespace {

// libpng reports errors by calling back and expecting a longjmp; this carries
// the jump target and the message out of the library.
struct PngFailure {
    std::jmp_buf jump;
    char message[200];
    int saved_errno;
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
    auto* failure = static_cast<PngFailure*>(png_get_error_ptr(png));
    failure->saved_errno = errno;
    std::snprintf(failure->message, sizeof failure->message, "%s", message);
    std::longjmp(failure->jump, 1);
}

// Warnings (none are expected when writing) must not reach the terminal.
void on_png_warning(png_structp, png_const_charp) {}

// Encodes 8-bit RGB rows to `out`. Holds no C++ object with a destructor, since
// libpng's longjmp would skip it. Returns false with `failure` filled on error.
bool encode_png(std::FILE* out, png_uint_32 width, png_uint_32 height, png_bytepp rows, PngFailure* failure) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, failure, on_png_error, on_png_warning);
    png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
    if (info == nullptr) {
        png_destroy_write_struct(&png, nullptr);
        std::snprintf(failure->message, sizeof failure->message, "out of memory");
        return false;
    }
    if (setjmp(failure->jump) != 0) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_user_limits(png, PNG_UINT_31_MAX, PNG_UINT_31_MAX);  // the PNG format's own limit
    png_init_io(png, out);
    // Paeth filtering with zlib's run-length strategy: several times faster
    // than libpng's default (adaptive filters, zlib level 6) on renders, for
    // files only a little larger.
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_PAETH);
    png_set_compression_strategy(png, Z_RLE);
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    // sRGB chunk, plus the gAMA and cHRM equivalents for readers that predate it.
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

namespace {

std::vector<png_bytep> row_pointers(std::vector<std::uint8_t>& bytes, ImageView image) {
    std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
    for (std::size_t j = 0; j < rows.size(); ++j)
        rows[j] = bytes.data() + j * static_cast<std::size_t>(image.width) * 3;
    return rows;
}

}  // namespace

void write_png(const std::filesystem::path& file, ImageView image, DisplayTransform display) {
    std::vector<std::uint8_t> bytes = display_bytes(image, display);
    std::vector<png_bytep> rows = row_pointers(bytes, image);

    OutputFile out = open_for_writing(file);
    PngFailure failure{};
    errno = 0;
    if (!encode_png(out.get(), static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height),
                    rows.data(), &failure)) {
        // libpng says only "Write Error" when fwrite fails; the OS knows why.
        if (std::strcmp(failure.message, "Write Error") == 0 && failure.saved_errno != 0)
            throw std::system_error(failure.saved_errno, std::generic_category());
        throw Error(file.string(), std::string("png: ") + failure.message);
    }
    finish_writing(std::move(out));
}

std::vector<std::uint8_t> encode_png_bytes(ImageView image, DisplayTransform display) {
    std::vector<std::uint8_t> bytes = display_bytes(image, display);
    std::vector<png_bytep> rows = row_pointers(bytes, image);
    // A memory stream lets the file encoder write into a buffer.
    char* buffer = nullptr;
    std::size_t size = 0;
    std::FILE* stream = open_memstream(&buffer, &size);
    if (stream == nullptr) throw std::bad_alloc();
    PngFailure failure{};
    const bool ok = encode_png(stream, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height),
                               rows.data(), &failure);
    std::fclose(stream);  // sets buffer and size
    std::vector<std::uint8_t> png(buffer, buffer + (ok ? size : 0));
    std::free(buffer);
    if (!ok) throw Error("png", failure.message);
    return png;
}

}  // namespace sombra
