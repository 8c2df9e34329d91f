#include "image/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <string>
#include <system_error>

#include "core/error.h"
#include "image/atomic_file.h"
#include "image/writers.h"

namespace sombra {

namespace fs = std::filesystem;

namespace {

std::string lower_case(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

// The folder a new file at `path` is created in; an empty parent means the current folder.
fs::path folder_of(const fs::path& path) {
    const fs::path parent = path.parent_path();
    return parent.empty() ? fs::path(".") : parent;
}

// Where the bytes really go: a symbolic link to an existing file is followed, so
// that writing through it updates the linked file rather than replacing the link.
fs::path resolve_target(const fs::path& path) {
    std::error_code error;
    if (!fs::is_symlink(path, error)) return path;
    fs::path resolved = fs::canonical(path, error);
    return error ? path : resolved;
}

// A JPEG holds at most 65,500 pixels a side (wider than any render, not
// than an array from Python).
void check_output_size(const fs::path& path, int width, int height) {
    if (image_format_for(path) == ImageFormat::Jpeg && (width > kMaxJpegSide || height > kMaxJpegSide))
        throw Error(path.string(), "a JPEG holds at most " + std::to_string(kMaxJpegSide) + " pixels a side, not " +
                                       std::to_string(width) + "x" + std::to_string(height));
}

}  // namespace

ImageFormat image_format_for(const fs::path& path) {
    const std::string extension = path.extension().string();
    const std::string lower = lower_case(extension);
    if (lower == ".png") return ImageFormat::Png;
    if (lower == ".jpg" || lower == ".jpeg") return ImageFormat::Jpeg;
    if (lower == ".pfm") return ImageFormat::Pfm;
    if (lower == ".exr") return ImageFormat::Exr;
    if (extension.empty()) throw Error(path.string(), "no image format extension (use .png, .jpg, .pfm or .exr)");
    throw Error(path.string(), "unsupported image format '" + extension.substr(1) + "' (use .png, .jpg, .pfm or .exr)");
}

void check_output_path(const fs::path& path) {
    image_format_for(path);
    const fs::path target = resolve_target(path);
    const fs::path folder = folder_of(target);
    std::error_code error;
    const fs::file_status folder_status = fs::status(folder, error);
    if (folder_status.type() == fs::file_type::none)
        throw Error(path.string(), "cannot access folder '" + folder.string() + "': " + errno_message(error.value()));
    if (!fs::exists(folder_status)) throw Error(path.string(), "folder '" + folder.string() + "' does not exist");
    if (!fs::is_directory(folder_status)) throw Error(path.string(), "'" + folder.string() + "' is not a folder");
    if (fs::is_directory(target, error)) throw Error(path.string(), "is a folder, not an image file");
    // Creating the temporary file and renaming it need write and search rights on the folder.
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw Error(path.string(), "folder '" + folder.string() + "' is not writable: " + errno_message(errno));
}

void write_image(const fs::path& path, ImageView image, DisplayTransform display, std::span<const ImageChannel> layers,
                 std::span<const ImageAttribute> attributes) {
    const ImageFormat format = image_format_for(path);
    if ((!layers.empty() || !attributes.empty()) && format != ImageFormat::Exr)
        throw Error(path.string(), "only an .exr file holds layers beside the image");
    if (image.width <= 0 || image.height <= 0)
        throw Error(path.string(), "cannot write an image of " + std::to_string(image.width) + "x" +
                                       std::to_string(image.height) + " pixels");
    if (image.rgb == nullptr) throw Error(path.string(), "cannot write: no pixel data");
    check_output_size(path, image.width, image.height);

    const fs::path target = resolve_target(path);
    try {
        write_file_atomically(target, [&](const fs::path& temp) {
            switch (format) {
                case ImageFormat::Png: write_png(temp, image, display); break;
                case ImageFormat::Jpeg: write_jpeg(temp, image, display); break;
                case ImageFormat::Pfm: write_pfm(temp, image); break;
                case ImageFormat::Exr: write_exr(temp, image, layers, attributes); break;
            }
        });
    } catch (const Error& e) {
        // Name the path the user gave, even when a link led elsewhere.
        throw Error(path.string(), e.message());
    }
}

}  // namespace sombra
