// Test helper: writing small float EXR files (with values the product's own
// writer would refuse or sanitise: negative, NaN, infinite), for the HDR
// image, scene-file and command-line tests of environment maps.
#pragma once

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <filesystem>
#include <string>
#include <vector>

namespace sombra::testing {

// Writes `rgb` (width × height, 3 floats per pixel) as a float EXR whose data
// window starts at `origin` (the display window is the same box), with the
// first channels.size() floats of each pixel stored under those names.
inline void write_exr(const std::filesystem::path& file, int width, int height, const std::vector<float>& rgb,
                      const Imath::V2i& origin = {0, 0}, const std::vector<std::string>& channels = {"R", "G", "B"}) {
    const Imath::Box2i window(origin, origin + Imath::V2i(width - 1, height - 1));
    Imf::Header header(window, window);
    Imf::FrameBuffer frame;
    const std::size_t x_stride = 3 * sizeof(float);
    for (std::size_t c = 0; c < channels.size(); ++c) {
        header.channels().insert(channels[c], Imf::Channel(Imf::FLOAT));
        frame.insert(channels[c], Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, window, x_stride,
                                                   x_stride * static_cast<std::size_t>(width)));
    }
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(height);
}

}  // namespace sombra::testing
