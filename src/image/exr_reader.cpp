// OpenEXR files read back whole (image_io.h: read_exr_channels), after
// sombra's own check of their layout (exr_check.h): the shards `sombra merge`
// joins (spec §21), and every EXR texture and environment map.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_limits.h"
#include "image/exr_check.h"
#include "image/image_io.h"

namespace sombra {

namespace {

// A library's message on one line (OpenEXR's may span several).
std::string one_line(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    std::replace(s.begin(), s.end(), '\r', ' ');
    return s;
}

}  // namespace

ExrChannels read_exr_channels(const std::filesystem::path& path, const std::vector<std::string>& only) {
    const std::string where = path.string();
    const int rows_per_chunk = check_exr_file(path, where);
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
        for (auto c = header.channels().begin(); c != header.channels().end(); ++c)
            if (only.empty() || std::find(only.begin(), only.end(), c.name()) != only.end())
                out.names.emplace_back(c.name());
        out.values.resize(out.names.size());
        // Read a chunk at a time, the channels growing only by rows that
        // decoded: a few hundred bytes can claim the largest image, and a
        // chunk that is not what it claims stops the read before its memory.
        const auto total = static_cast<std::size_t>(width * height);
        // With none of the channels asked for, there is nothing to read.
        for (std::int64_t first = window.min.y; !out.names.empty() && first <= window.max.y; first += rows_per_chunk) {
            const std::int64_t last = std::min<std::int64_t>(first + rows_per_chunk - 1, window.max.y);
            const auto needed = static_cast<std::size_t>((last - window.min.y + 1) * width);
            Imf::FrameBuffer frame;
            for (std::size_t k = 0; k < out.names.size(); ++k) {
                std::vector<float>& values = out.values[k];
                // Doubled as rows arrive, never past the whole image: it ends exactly full.
                if (needed > values.capacity())
                    values.reserve(std::min(total, std::max(needed, 2 * values.capacity())));
                values.resize(needed, 0.0f);
                // The slice's origin is moved so that the data window's corner lands on element 0.
                char* base = reinterpret_cast<char*>(values.data()) -
                             (std::ptrdiff_t{window.min.x} + std::ptrdiff_t{window.min.y} * width) *
                                 static_cast<std::ptrdiff_t>(sizeof(float));
                frame.insert(out.names[k], Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                                      sizeof(float) * static_cast<std::size_t>(width)));
            }
            file.setFrameBuffer(frame);
            file.readPixels(static_cast<int>(first), static_cast<int>(last));
        }
        for (auto a = header.begin(); a != header.end(); ++a)
            if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&a.attribute()))
                out.attributes.push_back({a.name(), text->value()});
        return out;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(where, "cannot read as OpenEXR: " + one_line(e.what()));
    }
}

}  // namespace sombra
