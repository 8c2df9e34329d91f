// Tests only: reads tev packets back (image/tev_packets.h describes the
// format) and paints the updates onto the created image, as tev would.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace sombra::testing {

struct TevImage {
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::vector<float> values;  // channels.size() floats a pixel, row-major
    int updates = 0;            // update packets received
    int creates = 0;
};

class TevDecoder {
public:
    std::map<std::string, TevImage> images;

    // Feeds bytes as they arrive; whole packets are applied, a partial one waits.
    void feed(const std::uint8_t* data, std::size_t size) {
        buffer_.insert(buffer_.end(), data, data + size);
        while (buffer_.size() >= 4) {
            const std::uint32_t length = read_u32(buffer_.data());
            if (length < 5) throw std::runtime_error("tev packet shorter than its header");
            if (buffer_.size() < length) return;
            apply(std::vector<std::uint8_t>(buffer_.begin(), buffer_.begin() + length));
            buffer_.erase(buffer_.begin(), buffer_.begin() + length);
        }
    }
    bool has_partial_packet() const { return !buffer_.empty(); }

private:
    static std::uint32_t read_u32(const std::uint8_t* p) {
        return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24;
    }

    struct Reader {
        const std::vector<std::uint8_t>& bytes;
        std::size_t at = 5;
        void need(std::size_t n) const {
            if (at + n > bytes.size()) throw std::runtime_error("tev packet ends inside a field");
        }
        std::uint8_t u8() {
            need(1);
            return bytes[at++];
        }
        std::int32_t i32() {
            need(4);
            const std::uint32_t v = read_u32(bytes.data() + at);
            at += 4;
            return static_cast<std::int32_t>(v);
        }
        std::int64_t i64() {
            const std::uint64_t lo = static_cast<std::uint32_t>(i32()), hi = static_cast<std::uint32_t>(i32());
            return static_cast<std::int64_t>(lo | hi << 32);
        }
        float f32() {
            const auto v = static_cast<std::uint32_t>(i32());
            float f = 0;
            std::memcpy(&f, &v, sizeof f);
            return f;
        }
        std::string str() {
            std::string s;
            for (std::uint8_t c = u8(); c != 0; c = u8()) s.push_back(static_cast<char>(c));
            return s;
        }
    };

    void apply(const std::vector<std::uint8_t>& packet) {
        Reader r{packet};
        const std::uint8_t type = packet[4];
        if (type == 4) {  // CreateImage
            r.u8();
            TevImage& image = images[r.str()];
            image.width = r.i32();
            image.height = r.i32();
            const int n = r.i32();
            image.channels.clear();
            for (int c = 0; c < n; ++c) image.channels.push_back(r.str());
            image.values.assign(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
                                    static_cast<std::size_t>(n),
                                0.0f);
            ++image.creates;
        } else if (type == 6) {  // UpdateImage, version 3
            r.u8();
            const std::string name = r.str();
            if (!images.count(name)) throw std::runtime_error("tev update of an image never created: " + name);
            TevImage& image = images[name];
            const int n = r.i32();
            std::vector<std::string> names;
            for (int c = 0; c < n; ++c) names.push_back(r.str());
            const int x = r.i32(), y = r.i32(), w = r.i32(), h = r.i32();
            std::vector<std::int64_t> offsets(static_cast<std::size_t>(n)), strides(static_cast<std::size_t>(n));
            for (auto& o : offsets) o = r.i64();
            for (auto& s : strides) s = r.i64();
            if (x < 0 || y < 0 || x + w > image.width || y + h > image.height)
                throw std::runtime_error("tev update outside the image");
            std::vector<float> data;
            while (r.at < packet.size()) data.push_back(r.f32());
            for (int c = 0; c < n; ++c) {
                std::size_t target = 0;
                while (target < image.channels.size() && image.channels[target] != names[static_cast<std::size_t>(c)])
                    ++target;
                if (target == image.channels.size()) throw std::runtime_error("tev update of an unknown channel");
                for (int py = 0; py < h; ++py)
                    for (int px = 0; px < w; ++px) {
                        const auto k = static_cast<std::size_t>(offsets[static_cast<std::size_t>(c)] +
                                                                (py * w + px) * strides[static_cast<std::size_t>(c)]);
                        if (k >= data.size()) throw std::runtime_error("tev update shorter than its region");
                        image.values[(static_cast<std::size_t>(y + py) * static_cast<std::size_t>(image.width) +
                                      static_cast<std::size_t>(x + px)) *
                                         image.channels.size() +
                                     target] = data[k];
                    }
            }
            ++image.updates;
        } else {
            throw std::runtime_error("tev packet of unexpected type " + std::to_string(type));
        }
    }

    std::vector<std::uint8_t> buffer_;
};

}  // namespace sombra::testing
