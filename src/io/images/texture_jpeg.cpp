// JPEG decoding with libjpeg-turbo: the header first (size, colour space),
// the limits checked, then the rows decoded into a buffer of exactly that size.
#include "io/images/texture_jpeg.h"

#include <csetjmp>
#include <cstddef>
#include <cstdio>
// jpeglib.h uses size_t and FILE without including their headers, and
// jerror.h (the message codes) needs jpeglib.h.
#include <jpeglib.h>
// (kept in this order)
#include <jerror.h>

#include "core/error.h"
#include "io/images/texture_image.h"

namespace sombra {

namespace {

// libjpeg reports errors through error_exit, which must not return: it jumps
// back to decode_jpeg with the reason. The progress monitor and the warnings
// that mean wrong pixels end the decode the same way.
struct JpegFailure {
    jpeg_error_mgr manager;
    jpeg_progress_mgr progress;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
    bool truncated;
};

JpegFailure& failure_of(j_common_ptr info) { return *reinterpret_cast<JpegFailure*>(info->err); }

[[noreturn]] void on_jpeg_error(j_common_ptr info) {
    (*info->err->format_message)(info, failure_of(info).message);
    std::longjmp(failure_of(info).jump, 1);
}

// libjpeg decodes on through corrupt data, filling what it cannot read with
// grey; those warnings are errors here, since the texture would be wrong.
// The rest (an unknown JFIF version, stray bytes between markers, a bad ICC
// profile) leave the pixels intact and are dropped, as are trace messages.
void on_jpeg_message(j_common_ptr info, int level) {
    if (level >= 0) return;
    switch (info->err->msg_code) {
        case JWRN_JPEG_EOF: failure_of(info).truncated = true; [[fallthrough]];
        case JWRN_HUFF_BAD_CODE:
        case JWRN_ARITH_BAD_CODE:
        case JWRN_HIT_MARKER:
        case JWRN_MUST_RESYNC:
        case JWRN_NOT_SEQUENTIAL:
        case JWRN_BOGUS_PROGRESSION: on_jpeg_error(info);
        default: return;
    }
}

void on_jpeg_progress(j_common_ptr info) {
    const auto* decompress = reinterpret_cast<j_decompress_ptr>(info);
    if (decompress->input_scan_number <= kMaxJpegScans) return;
    std::snprintf(failure_of(info).message, JMSG_LENGTH_MAX, "more than %d scans", kMaxJpegScans);
    std::longjmp(failure_of(info).jump, 1);
}

// CMYK as libjpeg returns it to RGB. Photoshop, which writes Adobe's marker,
// stores the inks inverted (255 = no ink): then R = C·K/255 on the stored values.
void cmyk_row_to_rgb(const JSAMPLE* cmyk, unsigned char* rgb, JDIMENSION width, bool inverted) {
    for (JDIMENSION x = 0; x < width; ++x, cmyk += 4, rgb += 3) {
        const auto ink = [&](int i) { return inverted ? unsigned{cmyk[i]} : 255u - cmyk[i]; };
        for (int c = 0; c < 3; ++c) rgb[c] = static_cast<unsigned char>((ink(c) * ink(3) + 127) / 255);
    }
}

// Frees libjpeg's memory however decode_jpeg leaves. Declared before the
// setjmp, so the error path's longjmp does not skip it.
struct DecompressGuard {
    jpeg_decompress_struct* info;
    explicit DecompressGuard(jpeg_decompress_struct* decompress) : info(decompress) {}
    DecompressGuard(const DecompressGuard&) = delete;
    DecompressGuard& operator=(const DecompressGuard&) = delete;
    ~DecompressGuard() { jpeg_destroy_decompress(info); }
};

// Decodes into `out`, the caller's, so that what is written to it after the
// setjmp is in memory when an error jumps back (C: locals changed between
// setjmp and longjmp are indeterminate).
void decode_into(std::span<const unsigned char> bytes, const std::string& where, DecodedPixels& out) {
    // Everything with a destructor is made before the setjmp (see the guard).
    JpegFailure failure{};
    jpeg_decompress_struct info{};
    const DecompressGuard guard(&info);
    info.err = jpeg_std_error(&failure.manager);
    failure.manager.error_exit = on_jpeg_error;
    failure.manager.emit_message = on_jpeg_message;
    failure.progress.progress_monitor = on_jpeg_progress;
    if (setjmp(failure.jump) != 0) {
        if (failure.truncated) throw Error(where, "JPEG file is truncated");
        throw Error(where, std::string("cannot decode as JPEG: ") + failure.message);
    }
    jpeg_create_decompress(&info);
    info.progress = &failure.progress;
    jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&info, TRUE);  // TRUE: a file of tables only is an error

    const bool cmyk = info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK;
    const bool grey = info.jpeg_color_space == JCS_GRAYSCALE;
    info.out_color_space = cmyk ? JCS_CMYK : grey ? JCS_GRAYSCALE : JCS_RGB;
    out.width = static_cast<int>(info.image_width);
    out.height = static_cast<int>(info.image_height);
    out.channels = grey ? 1 : 3;
    check_texture_size(where, out.width, out.height, out.channels);

    jpeg_start_decompress(&info);
    const std::size_t stride = std::size_t{info.output_width} * static_cast<std::size_t>(out.channels);
    out.pixels.resize(stride * info.output_height);
    // A CMYK row is decoded into libjpeg's own memory (freed with the decompressor), then converted.
    JSAMPARRAY cmyk_row =
        cmyk ? (*info.mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(&info), JPOOL_IMAGE, info.output_width * 4, 1)
             : nullptr;
    while (info.output_scanline < info.output_height) {
        unsigned char* row = out.pixels.data() + stride * info.output_scanline;
        JSAMPROW target = cmyk ? cmyk_row[0] : row;
        jpeg_read_scanlines(&info, &target, 1);
        if (cmyk) cmyk_row_to_rgb(cmyk_row[0], row, info.output_width, info.saw_Adobe_marker != 0);
    }
    // Reads on to the end-of-image marker, so that a file cut anywhere is
    // refused, not only one cut before libjpeg's read-ahead reached its pixels.
    jpeg_finish_decompress(&info);
}

}  // namespace

DecodedPixels decode_jpeg(std::span<const unsigned char> bytes, const std::string& where) {
    // 0xff fill bytes may come before the start-of-image marker (stb took
    // them); libjpeg wants the marker's own 0xff first.
    std::size_t fill = 0;
    while (fill + 1 < bytes.size() && bytes[fill + 1] == 0xff) ++fill;
    DecodedPixels out;
    decode_into(bytes.subspan(fill), where, out);
    return out;
}

}  // namespace sombra
