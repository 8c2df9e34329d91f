// JPEG output (spec §27): 8-bit sRGB through libjpeg, quality 95.
#include <cerrno>
#include <csetjmp>
#include <cstddef>
#include <cstdio>
// jpeglib.h uses size_t and FILE without including their headers, and
// jerror.h (the message codes) needs jpeglib.h.
#include <jpeglib.h>
// (kept in this order)
#include <jerror.h>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/error.h"
#include "image/display_transform.h"
#include "image/writers.h"

namespace sombra {

namespace {

constexpr int kJpegQuality = 95;
static_assert(kMaxJpegSide == JPEG_MAX_DIMENSION);

// libjpeg reports errors through error_exit, which must not return; it
// jumps back to encode_jpeg with the library's message.
struct JpegFailure {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
    int saved_errno;
};

[[noreturn]] void on_jpeg_error(j_common_ptr info) {
    auto* failure = reinterpret_cast<JpegFailure*>(info->err);
    failure->saved_errno = errno;
    (*info->err->format_message)(info, failure->message);
    std::longjmp(failure->jump, 1);
}

// Warnings (none are expected when writing) must not reach the terminal.
void on_jpeg_message(j_common_ptr, int) {}

// Encodes 8-bit RGB rows to `out`. Holds no C++ object with a destructor,
// since the error path's longjmp would skip it. False with `failure` filled on error.
bool encode_jpeg(std::FILE* out, JDIMENSION width, JDIMENSION height, const std::uint8_t* rgb, JpegFailure* failure) {
    jpeg_compress_struct info{};
    info.err = jpeg_std_error(&failure->manager);
    failure->manager.error_exit = on_jpeg_error;
    failure->manager.emit_message = on_jpeg_message;
    if (setjmp(failure->jump) != 0) {
        jpeg_destroy_compress(&info);
        return false;
    }
    jpeg_create_compress(&info);
    jpeg_stdio_dest(&info, out);
    info.image_width = width;
    info.image_height = height;
    info.input_components = 3;
    info.in_color_space = JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, kJpegQuality, TRUE);
    jpeg_start_compress(&info, TRUE);
    while (info.next_scanline < info.image_height) {
        // libjpeg takes non-const rows but only reads them.
        auto* row = const_cast<JSAMPLE*>(rgb + static_cast<std::size_t>(info.next_scanline) * width * 3);
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    return true;
}

}  // namespace

void write_jpeg(const std::filesystem::path& file, ImageView image, DisplayTransform display) {
    if (image.width > kMaxJpegSide || image.height > kMaxJpegSide)
        throw Error(file.string(), "a JPEG holds at most " + std::to_string(kMaxJpegSide) + " pixels a side");
    const std::vector<std::uint8_t> bytes = display_bytes(image, display);
    OutputFile out = open_for_writing(file);
    JpegFailure failure{};
    errno = 0;
    if (!encode_jpeg(out.get(), static_cast<JDIMENSION>(image.width), static_cast<JDIMENSION>(image.height),
                     bytes.data(), &failure)) {
        // libjpeg says only that the write failed; the OS knows why.
        if (failure.manager.msg_code == JERR_FILE_WRITE && failure.saved_errno != 0)
            throw std::system_error(failure.saved_errno, std::generic_category());
        throw Error(file.string(), std::string("jpeg: ") + failure.message);
    }
    finish_writing(std::move(out));
}

}  // namespace sombra
