// OpenEXR files read back whole (image_io.h: read_exr_channels), for
// `sombra merge` (spec §21), which joins the shards a render wrote.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>

#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_limits.h"
#include "image/image_io.h"

namespace sombra {

ExrChannels read_exr_channels(const std::filesystem::path& path) {
    const std::string where = path.string();
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
