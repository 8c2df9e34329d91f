#include "io/ply/ply_binary_stream.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>

namespace sombra {

PlyBinaryStream::PlyBinaryStream(std::FILE* file, std::string_view already_read, std::uint64_t body_offset,
                                 std::uint64_t file_size, bool swap_bytes, const std::string* where)
    : file_(file),
      buffer_(already_read.begin(), already_read.end()),
      end_(already_read.size()),
      buffer_offset_(body_offset),
      file_size_(file_size),
      swap_bytes_(swap_bytes),
      where_(where) {}

bool PlyBinaryStream::refill(std::size_t bytes) {
    // Keep the unread tail, then read one slice after it.
    const std::size_t left = end_ - at_;
    std::memmove(buffer_.data(), buffer_.data() + at_, left);
    buffer_offset_ += at_;
    at_ = 0;
    end_ = left;
    buffer_.resize(std::max(buffer_.size(), left + kPlyStreamSlice));
    while (end_ < bytes) {
        const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
        if (got == 0) {
            if (std::ferror(file_)) throw Error(*where_, std::string("cannot read: ") + std::strerror(errno));
            return false;
        }
        end_ += got;
    }
    return true;
}

void PlyBinaryStream::skip(std::size_t bytes) {
    if (bytes > remaining()) fail("unexpected end of file");
    while (bytes > 0) {
        if (at_ == end_ && !refill(1)) fail("unexpected end of file");
        const std::size_t step = std::min(bytes, end_ - at_);
        at_ += step;
        bytes -= step;
    }
}

double PlyBinaryStream::number(PlyType type) {
    switch (type) {
        case PlyType::Int8: return load<std::int8_t>();
        case PlyType::UInt8: return load<std::uint8_t>();
        case PlyType::Int16: return load<std::int16_t>();
        case PlyType::UInt16: return load<std::uint16_t>();
        case PlyType::Int32: return load<std::int32_t>();
        case PlyType::UInt32: return load<std::uint32_t>();
        case PlyType::Float32: return std::bit_cast<float>(load<std::uint32_t>());
        case PlyType::Float64: return std::bit_cast<double>(load<std::uint64_t>());
    }
    return 0;
}

std::int64_t PlyBinaryStream::integer(PlyType type, const char* what) {
    const double value = number(type);
    if (!(std::fabs(value) < 9e15) || value != std::floor(value)) {
        at_ -= ply_type_size(type);  // the value's bytes are still in the buffer: name its offset
        fail(std::string(what) + " is not an integer");
    }
    return static_cast<std::int64_t>(value);
}

}  // namespace sombra
