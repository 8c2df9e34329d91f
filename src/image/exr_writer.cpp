#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <new>
#include <utility>
#include <vector>

#include "core/error.h"
#include "image/writers.h"

namespace sombra {

namespace {

// OpenEXR's own file stream swallows errors when it closes; this one checks
// every write and remembers the first failure, which OpenEXR's destructor
// (it writes the line-offset table) would otherwise hide.
class CheckedStream : public Imf::OStream {
public:
    CheckedStream(std::FILE* file, const char* name) : Imf::OStream(name), file_(file) {}

    void write(const char data[], int size) override {
        if (std::fwrite(data, 1, static_cast<std::size_t>(size), file_) != static_cast<std::size_t>(size)) fail();
    }
    std::uint64_t tellp() override {
        const off_t position = ::ftello(file_);
        if (position < 0) fail();
        return static_cast<std::uint64_t>(position);
    }
    void seekp(std::uint64_t position) override {
        if (position > static_cast<std::uint64_t>(std::numeric_limits<off_t>::max()) ||
            ::fseeko(file_, static_cast<off_t>(position), SEEK_SET) != 0)
            fail();
    }
    // The errno of the first failed operation, 0 when all succeeded.
    int failure() const { return failure_; }

private:
    [[noreturn]] void fail() {
        if (failure_ == 0) failure_ = errno != 0 ? errno : EIO;
        throw std::system_error(failure_, std::generic_category());
    }
    std::FILE* file_;
    int failure_ = 0;
};

// The EXR file of write_exr written to `out` (a file or a memory stream); throws on failure.
void encode_exr(std::FILE* out, const char* name, ImageView image, std::span<const ImageChannel> layers,
                std::span<const ImageAttribute> attributes) {
    const auto width = static_cast<std::size_t>(image.width);
    const auto height = static_cast<std::size_t>(image.height);

    // A copy, so that non-finite pixels can be written as black.
    std::vector<float> pixels(image.rgb, image.rgb + width * height * 3);
    for (std::size_t pixel = 0; pixel < width * height; ++pixel)
        if (!pixel_is_finite(pixels.data(), pixel))
            pixels[3 * pixel] = pixels[3 * pixel + 1] = pixels[3 * pixel + 2] = 0.0f;

    Imf::Header header(image.width, image.height);  // ZIP compression: lossless
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    const std::size_t pixel_stride = 3 * sizeof(float);
    for (std::size_t c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data() + c), pixel_stride,
                                          pixel_stride * width));
    }
    for (const ImageChannel& layer : layers) {
        const std::size_t stride = static_cast<std::size_t>(layer.stride) * sizeof(float);
        header.channels().insert(layer.name, Imf::Channel(Imf::FLOAT));
        // OpenEXR's slices take a writable pointer but only read when writing.
        frame.insert(layer.name, Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(layer.values)),
                                            stride, stride * width));
    }

    for (const ImageAttribute& a : attributes) header.insert(a.name, Imf::StringAttribute(a.value));

    CheckedStream stream(out, name);
    {
        Imf::OutputFile exr(stream, header);  // single-threaded: the global OpenEXR thread count is 0
        exr.setFrameBuffer(frame);
        exr.writePixels(image.height);
    }
    if (stream.failure() != 0) throw std::system_error(stream.failure(), std::generic_category());
}

}  // namespace

// 32-bit float channels rather than half: the file holds exactly the radiance
// the renderer computed (half would round to 11 bits and overflow above 65504).
void write_exr(const std::filesystem::path& file, ImageView image, std::span<const ImageChannel> layers,
               std::span<const ImageAttribute> attributes) {
    OutputFile out = open_for_writing(file);
    encode_exr(out.get(), file.c_str(), image, layers, attributes);
    finish_writing(std::move(out));
}

std::vector<std::uint8_t> encode_exr_bytes(ImageView image) {
    // A memory stream lets the file encoder write into a buffer (it seeks
    // back to write the line-offset table, which open_memstream allows).
    char* buffer = nullptr;
    std::size_t size = 0;
    std::FILE* stream = open_memstream(&buffer, &size);
    if (stream == nullptr) throw std::bad_alloc();
    bool ok = true;
    try {
        encode_exr(stream, "exr", image, {}, {});
    } catch (...) {
        ok = false;
    }
    ok = std::fflush(stream) == 0 && ok;
    std::fclose(stream);  // sets buffer and size
    std::vector<std::uint8_t> exr(buffer, buffer + (ok ? size : 0));
    std::free(buffer);
    if (!ok) throw Error("exr", "encoding the image failed");
    return exr;
}

}  // namespace sombra
