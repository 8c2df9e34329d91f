#include "scene/polygon_file.h"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.h"

namespace sombra {
namespace {

// strerror's text with a lower-case first letter, as our messages are.
std::string reason(int err) {
    std::string text = std::strerror(err);
    if (!text.empty()) text[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
    return text;
}

}  // namespace

std::string read_polygon_file(const std::filesystem::path& path) {
    namespace fs = std::filesystem;
    const std::string where = path.string();
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (status.type() == fs::file_type::not_found) throw Error(where, "no such file");
    if (ec) throw Error(where, "cannot read: " + ec.message());
    if (status.type() == fs::file_type::directory) throw Error(where, "is a folder, not a mesh file");
    // A FIFO or device could block forever or never end.
    if (status.type() != fs::file_type::regular) throw Error(where, "is not a regular file");

    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw Error(where, "cannot open: " + reason(errno));
    std::string bytes;
    const std::uintmax_t size_on_disk = fs::file_size(path, ec);
    if (!ec) bytes.reserve(static_cast<std::size_t>(size_on_disk));
    char chunk[1 << 16];
    std::size_t got = 0;
    // Read to the end rather than trusting the size on disk, which may change underneath.
    while ((got = std::fread(chunk, 1, sizeof chunk, file.get())) > 0) bytes.append(chunk, got);
    if (std::ferror(file.get())) throw Error(where, "cannot read: " + reason(errno));
    return bytes;
}

}  // namespace sombra
