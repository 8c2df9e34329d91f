// WebP decoding with libwebp: the header's features first (size, alpha,
// animation), the limits checked, then the pixels decoded into a buffer of
// exactly that size.
#include "io/images/texture_webp.h"

#include <webp/decode.h>

#include "core/error.h"
#include "io/images/texture_image.h"

namespace sombra {

namespace {

std::string status_name(VP8StatusCode status) {
    switch (status) {
        case VP8_STATUS_OK: return "no error";
        case VP8_STATUS_OUT_OF_MEMORY: return "out of memory";
        case VP8_STATUS_INVALID_PARAM: return "invalid parameter";
        case VP8_STATUS_BITSTREAM_ERROR: return "a corrupt bitstream";
        case VP8_STATUS_UNSUPPORTED_FEATURE: return "an unsupported feature";
        case VP8_STATUS_SUSPENDED: return "suspended";
        case VP8_STATUS_USER_ABORT: return "aborted";
        case VP8_STATUS_NOT_ENOUGH_DATA: return "the data ends too early (truncated?)";
    }
    return "unknown reason";
}

}  // namespace

DecodedPixels decode_webp(std::span<const unsigned char> bytes, const std::string& where) {
    WebPBitstreamFeatures features;
    if (const VP8StatusCode status = WebPGetFeatures(bytes.data(), bytes.size(), &features); status != VP8_STATUS_OK)
        throw Error(where, "cannot read the WebP header: " + status_name(status));
    if (features.has_animation) throw Error(where, "animated WebP images are not supported");
    DecodedPixels out;
    out.width = features.width;
    out.height = features.height;
    out.channels = features.has_alpha ? 4 : 3;
    check_texture_size(where, out.width, out.height, out.channels);
    const std::size_t row = static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.channels);
    out.pixels.resize(row * static_cast<std::size_t>(out.height));
    const uint8_t* decoded = features.has_alpha ? WebPDecodeRGBAInto(bytes.data(), bytes.size(), out.pixels.data(),
                                                                     out.pixels.size(), static_cast<int>(row))
                                                : WebPDecodeRGBInto(bytes.data(), bytes.size(), out.pixels.data(),
                                                                    out.pixels.size(), static_cast<int>(row));
    if (decoded == nullptr) {
        // The features again, to say why: a short file reads as not enough data.
        WebPBitstreamFeatures again;
        const VP8StatusCode status = WebPGetFeatures(bytes.data(), bytes.size(), &again);
        throw Error(where,
                    "cannot decode as WebP: " +
                        (status != VP8_STATUS_OK ? status_name(status) : std::string("a corrupt or truncated image")));
    }
    return out;
}

}  // namespace sombra
