// Film → file: PNG and JPEG (8-bit sRGB), PFM (32-bit float) and OpenEXR (linear).
// Every write is atomic: the image goes to a temporary file in the target's
// folder, which is renamed over the target only once complete, so a failed
// run never leaves a partial file or spoils an existing one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace sombra {

// Linear RGB radiance, row-major, top row first, 3 floats per pixel.
struct ImageView {
    int width = 0;
    int height = 0;
    const float* rgb = nullptr;
};

// One more 32-bit float channel for an OpenEXR file, e.g. "albedo.R" or
// "depth.Z" (spec §18's AOV layers): `stride` floats apart in row-major
// order, top row first, so that the 3-float AOV images give their channels
// without a copy. Written as they are, +∞ included.
struct ImageChannel {
    std::string name;
    const float* values = nullptr;
    int stride = 1;
};

// A text attribute of an OpenEXR file's header (a shard's identity, spec §21).
struct ImageAttribute {
    std::string name;
    std::string value;
};

// none: each channel clamped to [0, 1] (spec §1's PNG); pbr-neutral:
// Khronos' PBR Neutral tone mapper, which keeps base colours up to 0.76
// unchanged and compresses brighter ones toward white.
enum class Tonemap : std::uint8_t { None, PbrNeutral };

// What 8-bit outputs do to radiance before sRGB encoding: × 2^exposure,
// then `tonemap`. PFM and EXR keep linear radiance.
struct DisplayTransform {
    float exposure = 0;
    Tonemap tonemap = Tonemap::None;
};

enum class ImageFormat { Png, Jpeg, Pfm, Exr };

// The format named by the path's extension (case-insensitive .png, .jpg,
// .jpeg, .pfm, .exr). Throws Error(path, ...) for any other extension.
ImageFormat image_format_for(const std::filesystem::path& path);

// Checks, before any rendering, that `path` can be written: known extension,
// parent folder exists and is a writable folder, path is not a folder.
// Throws Error(path, ...) otherwise.
void check_output_path(const std::filesystem::path& path);

// True for the 8-bit formats that `DisplayTransform` applies to (PNG, JPEG).
inline bool is_eight_bit(ImageFormat format) { return format == ImageFormat::Png || format == ImageFormat::Jpeg; }

// Writes the image in the format of the path's extension. `display` (the
// exposure, the tone mapper) applies to PNG and JPEG only: PFM and EXR
// keep linear radiance.
// Pixels with a non-finite channel are written as black in every format.
// `layers` and `attributes` (EXR only; Error(path, ...) with another
// format) go into the file beside R, G, B and into its header. Throws
// Error(path, ...) on failure, leaving any earlier file at `path` untouched.
void write_image(const std::filesystem::path& path, ImageView image, DisplayTransform display,
                 std::span<const ImageChannel> layers = {}, std::span<const ImageAttribute> attributes = {});

// A PFM file read back: linear RGB, top row first; a grey ("Pf") file
// gives three equal channels. Throws Error(path, what) for a file that is
// not a PFM, whose size does not match its header, or of more than
// kMaxImageSide a side (core/image_limits.h).
struct PfmImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
};
PfmImage read_pfm(const std::filesystem::path& path);

// An OpenEXR file read back whole: every channel as 32-bit floats (row-major,
// top row first) and the header's text attributes.
struct ExrChannels {
    int width = 0, height = 0;
    std::vector<std::string> names;          // in the file's (alphabetical) order
    std::vector<std::vector<float>> values;  // one per name, width × height
    std::vector<ImageAttribute> attributes;  // the string attributes
};
// Reads `path`: every channel, or only those named in `only` that the file
// has (none when it has none of them); the data window's corner is pixel
// (0, 0). Throws Error(path, what) with a one-line `what` for a file that is
// not a single-part flat EXR, scanline or tiled (a tiled one reads as its
// first level; image/exr_check.h says what is checked before OpenEXR reads
// a byte), or that OpenEXR cannot read ("cannot read as OpenEXR: ...").
// sombra merge reads its shards with it, io/images/hdr_image.h its textures
// and environment maps.
ExrChannels read_exr_channels(const std::filesystem::path& path, const std::vector<std::string>& only = {});

// The bytes of the PNG file write_image would write for `image` (for
// embedding, e.g. in `sombra explain`'s SVG). Throws Error("png", ...) on failure.
std::vector<std::uint8_t> encode_png_bytes(ImageView image, DisplayTransform display);

// The bytes of the EXR file write_image would write for `image` without
// layers (32-bit float R, G, B, linear; the viewer's "save EXR"). Throws
// Error("exr", ...) on failure.
std::vector<std::uint8_t> encode_exr_bytes(ImageView image);

}  // namespace sombra
