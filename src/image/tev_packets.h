// Packets of tev's network protocol. The HDR image viewer tev listens on
// TCP (port 14158 by default) for packets that create an image and update
// its pixels; pbrt-v4's and Mitsuba's renderers stream to it this way, and
// so does `sombra render --display-server HOST:PORT` (spec §20).
//
// Every packet: its whole length (uint32, little-endian, these four bytes
// included), a type byte, then fields: strings UTF-8 and NUL-terminated,
// integers little-endian. sombra sends two types:
//   CreateImage (4): grab_focus (1 byte), name, width, height, channel
//     count (int32 each), the channel names;
//   UpdateImage, version 3 (6): grab_focus, name, channel count, channel
//     names, x, y, width, height of the region (int32), each channel's
//     offset then each channel's stride (int64, in floats), then the
//     region's floats.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "image/image_io.h"

namespace sombra {

inline constexpr std::uint8_t kTevCreateImage = 4;
inline constexpr std::uint8_t kTevUpdateImageV3 = 6;

// Regions of at most this many pixels go in one update packet (1 MiB of RGB
// floats), so a large image reaches tev in pieces it shows as they come.
inline constexpr int kTevMaxRegionPixels = 1 << 16;

// CreateImage: an image `name` of width × height with channels R, G, B.
std::vector<std::uint8_t> tev_create_image_packet(std::string_view name, int width, int height);

// UpdateImage (v3) packets carrying all of `image` as channels R, G, B:
// bands of whole rows, each at most kTevMaxRegionPixels pixels (at least one
// row). A pixel with a non-finite channel is sent black, as the image files
// write it.
std::vector<std::vector<std::uint8_t>> tev_update_image_packets(std::string_view name, ImageView image);

}  // namespace sombra
