// OpenEXR files read back whole (image_io.h: read_exr_channels), for
// `sombra merge` (spec §21), which joins the shards a render wrote.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_limits.h"
#include "image/image_io.h"

namespace sombra {

namespace {

// OpenEXR allocates what a header claims (an attribute's size, the offset
// table of the data window's height) before it reads the bytes; a hostile
// file of a few bytes could claim gigabytes. So the header is walked here
// first: every attribute must lie inside the file, and the data and display
// windows inside the image limits. Throws Error(where, ...).
void check_exr_header(const std::filesystem::path& path, const std::string& where) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw Error(where, "cannot read it");
    const auto size = static_cast<std::uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
    // The header is all a check needs, and it is small (a sombra shard's is under 1 KiB).
    std::vector<char> bytes(static_cast<std::size_t>(std::min<std::uint64_t>(size, 1 << 20)));
    in.seekg(0);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    const auto u32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(k)]);
        return v;
    };
    if (bytes.size() < 8 || u32(0) != 20000630u) throw Error(where, "not an EXR file (no EXR magic number)");
    const std::uint32_t flags = u32(4);
    if ((flags & 0xffu) != 2u || (flags & 0x1800u) != 0u)
        throw Error(where, "not a single-part flat EXR file of version 2");
    std::size_t at = 8;
    const auto c_string = [&]() {
        const std::size_t start = at;
        while (at < bytes.size() && bytes[at] != '\0') ++at;
        if (at >= bytes.size() || at - start > 255) throw Error(where, "damaged EXR header");
        return std::string(bytes.data() + start, bytes.data() + at++);
    };
    while (true) {
        const std::string name = c_string();
        if (name.empty()) return;  // the header's end
        const std::string type = c_string();
        if (at + 4 > bytes.size()) throw Error(where, "damaged EXR header");
        const std::uint32_t length = u32(at);
        at += 4;
        if (length > bytes.size() - at)
            throw Error(where, "damaged EXR header: attribute '" + name + "' claims " + std::to_string(length) +
                                   " bytes past the file");
        if (type == "box2i" && length == 16) {
            const auto coordinate = [&](std::size_t k) {
                return static_cast<std::int64_t>(static_cast<std::int32_t>(u32(at + 4 * k)));
            };
            const std::int64_t width = coordinate(2) - coordinate(0) + 1, height = coordinate(3) - coordinate(1) + 1;
            if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide ||
                width * height > kMaxPixels)
                throw Error(where, "an EXR " + name + " of " + std::to_string(width) + "x" + std::to_string(height) +
                                       " pixels is outside the image limits");
        }
        at += length;
    }
}

}  // namespace

ExrChannels read_exr_channels(const std::filesystem::path& path) {
    const std::string where = path.string();
    check_exr_header(path, where);
    try {
        Imf::InputFile file(path.c_str());  // single-threaded: the global OpenEXR thread count is 0
        const Imf::Header& header = file.header();
        const Imath::Box2i window = header.dataWindow();
        const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
        const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
        // Checked before any pixel is allocated: the header's claim is the file's word only.
        if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxPixels)
            throw Error(where, "an EXR image of " + std::to_string(width) + "x" + std::to_string(height) +
                                   " pixels is outside the image limits");
        ExrChannels out;
        out.width = static_cast<int>(width);
        out.height = static_cast<int>(height);
        Imf::FrameBuffer frame;
        const auto pixels = static_cast<std::size_t>(width * height);
        for (auto c = header.channels().begin(); c != header.channels().end(); ++c) out.names.emplace_back(c.name());
        out.values.resize(out.names.size());
        const std::size_t stride = sizeof(float);
        for (std::size_t k = 0; k < out.names.size(); ++k) {
            out.values[k].assign(pixels, 0.0f);
            // The slice's origin is moved so that the data window's corner lands on element 0.
            char* base =
                reinterpret_cast<char*>(out.values[k].data()) -
                (static_cast<std::ptrdiff_t>(window.min.x) + static_cast<std::ptrdiff_t>(window.min.y) * width) *
                    static_cast<std::ptrdiff_t>(stride);
            frame.insert(out.names[k], Imf::Slice(Imf::FLOAT, base, stride, stride * static_cast<std::size_t>(width)));
        }
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        for (auto a = header.begin(); a != header.end(); ++a)
            if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&a.attribute()))
                out.attributes.push_back({a.name(), text->value()});
        return out;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(where, std::string("not a readable EXR file: ") + e.what());
    }
}

}  // namespace sombra
