// Texture lookups (bilinear, wrap modes), the sRGB transfer function and the
// texture table; decoding lives in texture_image.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "scene/texture.h"

namespace sombra {

namespace {

// The coordinate reduced to a range where texel indices stay small: [0, 1)
// for repeat, [0, 2) for mirrored repeat (one period each), [-1, 2] for clamp
// (enough to reach past the edge texels' centres).
float reduce(float u, TextureWrap wrap) {
    if (!std::isfinite(u)) return 0.0f;
    switch (wrap) {
        case TextureWrap::Repeat: return u - std::floor(u);
        case TextureWrap::MirroredRepeat: return u - 2.0f * std::floor(0.5f * u);
        case TextureWrap::Clamp: break;
    }
    return std::clamp(u, -1.0f, 2.0f);
}

// The texel index i (any integer near [−n, 2n]) wrapped into [0, n).
int wrap_index(int i, int n, TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::Repeat: return ((i % n) + n) % n;
        case TextureWrap::MirroredRepeat: {
            const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
            return m < n ? m : 2 * n - 1 - m;
        }
        case TextureWrap::Clamp: break;
    }
    return std::clamp(i, 0, n - 1);
}

// The two texel indices around coordinate u (in texture units) and the weight of the second.
struct Span {
    int i0, i1;
    float f;
};
Span span(float u, int n, TextureWrap wrap) {
    const float x = reduce(u, wrap) * static_cast<float>(n) - 0.5f;
    const float base = std::floor(x);
    const int i = static_cast<int>(base);
    return {wrap_index(i, n, wrap), wrap_index(i + 1, n, wrap), x - base};
}

// The RGBA of texel (column x, row y from the top) of a grid `width` texels wide.
Rgba texel(const float* texels, int width, int channels, int x, int y) {
    const std::size_t at =
        (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
        static_cast<std::size_t>(channels);
    const float* p = texels + at;
    switch (channels) {
        case 1: return {p[0], p[0], p[0], 1.0f};
        case 2: return {p[0], p[0], p[0], p[1]};
        case 3: return {p[0], p[1], p[2], 1.0f};
        default: return {p[0], p[1], p[2], p[3]};
    }
}

}  // namespace

namespace {
double srgb_eotf(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
}  // namespace

float srgb_to_linear(float c) { return static_cast<float>(srgb_eotf(c)); }

float srgb_decode(unsigned code, unsigned max_code) {
    return static_cast<float>(srgb_eotf(static_cast<double>(code) / static_cast<double>(max_code)));
}

Rgba eval_texture(const Texture& t, Vec2 uv, TextureWrap wrap_u, TextureWrap wrap_v) {
    return eval_texels(t.texels.data(), t.width, t.height, t.channels, uv, wrap_u, wrap_v);
}

Rgba eval_texels(const float* texels, int width, int height, int channels, Vec2 uv, TextureWrap wrap_u,
                 TextureWrap wrap_v) {
    const Span s = span(uv.x, width, wrap_u);
    const Span r = span(uv.y, height, wrap_v);
    // Rows count from the bottom in uv, from the top in memory.
    const int y0 = height - 1 - r.i0, y1 = height - 1 - r.i1;
    const Rgba a = texel(texels, width, channels, s.i0, y0), b = texel(texels, width, channels, s.i1, y0);
    const Rgba c = texel(texels, width, channels, s.i0, y1), d = texel(texels, width, channels, s.i1, y1);
    Rgba out;
    for (std::size_t k = 0; k < 4; ++k) {
        const float bottom = (1.0f - s.f) * a[k] + s.f * b[k];
        const float top = (1.0f - s.f) * c[k] + s.f * d[k];
        out[k] = (1.0f - r.f) * bottom + r.f * top;
    }
    return out;
}

namespace {

// The index of an entry of `table` with the source and encoding of `texture`, or kNoEntry.
constexpr std::size_t kNoEntry = static_cast<std::size_t>(-1);
std::size_t find_texture(const std::vector<Texture>& table, const Texture& texture) {
    for (std::size_t i = 0; i < table.size(); ++i)
        if (table[i].source == texture.source && table[i].encoding == texture.encoding) return i;
    return kNoEntry;
}

}  // namespace

std::uint32_t add_texture(std::vector<Texture>& table, const Texture& texture) {
    if (const std::size_t i = find_texture(table, texture); i != kNoEntry) return static_cast<std::uint32_t>(i);
    table.push_back(texture);
    return static_cast<std::uint32_t>(table.size() - 1);
}

std::uint32_t add_texture(std::vector<Texture>& table, Texture&& texture) {
    if (const std::size_t i = find_texture(table, texture); i != kNoEntry) return static_cast<std::uint32_t>(i);
    table.push_back(std::move(texture));
    return static_cast<std::uint32_t>(table.size() - 1);
}

}  // namespace sombra
