// The largest image sombra makes or reads: anything beyond is a mistake, not
// a request (a 100000-pixel-wide render, a corrupt header claiming a billion
// pixels). Render settings (render/render_settings.h) and the image
// decoders (io/images/) check against the same numbers.
#pragma once

#include <cstdint>

namespace sombra {

inline constexpr int kMaxImageSide = 32768;
inline constexpr std::int64_t kMaxPixels = std::int64_t{1} << 28;

}  // namespace sombra
