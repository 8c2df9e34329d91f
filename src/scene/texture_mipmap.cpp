#include "scene/texture_mipmap.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>

namespace sombra {

namespace {

// The input texels one output texel averages along one axis, with weights.
// An input side n shrinks to m = ⌊n/2⌋; in units of 1/m of an input texel,
// output i spans [i·n, (i + 1)·n) and input k spans [k·m, (k + 1)·m), so
// every overlap is an integer and the weights are exact ratios, overlap / n.
// At most 3 inputs overlap one output (the span is 2 + (n − 2m)/m ≤ 3 texels,
// and starts at a multiple of 1/m).
struct BoxTaps {
    int first = 0;
    int count = 0;
    std::array<double, 3> weight{};
};

std::vector<BoxTaps> box_taps(int n, int m) {
    std::vector<BoxTaps> taps(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) {
        const long long lo = static_cast<long long>(i) * n, hi = lo + n;
        BoxTaps& t = taps[static_cast<std::size_t>(i)];
        t.first = static_cast<int>(lo / m);
        for (int k = t.first; static_cast<long long>(k) * m < hi; ++k) {
            const long long overlap =
                std::min(hi, static_cast<long long>(k + 1) * m) - std::max(lo, static_cast<long long>(k) * m);
            assert(t.count < 3);
            t.weight[static_cast<std::size_t>(t.count++)] = static_cast<double>(overlap) / static_cast<double>(n);
        }
    }
    return taps;
}

// The level below `from` (from's sides both >= 2), `channels` floats a texel.
TextureLevel half_level(const float* from, int width, int height, int channels) {
    TextureLevel to;
    to.width = width / 2;
    to.height = height / 2;
    to.texels.resize(static_cast<std::size_t>(to.width) * static_cast<std::size_t>(to.height) *
                     static_cast<std::size_t>(channels));
    const auto c = static_cast<std::size_t>(channels);
    if (width % 2 == 0 && height % 2 == 0) {
        // Both sides even (every level of a power-of-two texture): plain 2 × 2
        // averages, what the taps below give with all four weights ¼, without
        // their bookkeeping per texel.
        const std::size_t row = static_cast<std::size_t>(width) * c;
        tbb::parallel_for(tbb::blocked_range<int>(0, to.height, 16), [&](const tbb::blocked_range<int>& range) {
            for (int y = range.begin(); y < range.end(); ++y) {
                const float* top = from + static_cast<std::size_t>(2 * y) * row;
                const float* bottom = top + row;
                float* out = to.texels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(to.width) * c;
                for (std::size_t x = 0; x < static_cast<std::size_t>(to.width); ++x)
                    for (std::size_t k = 0; k < c; ++k) {
                        const std::size_t left = 2 * x * c + k, right = left + c;
                        const double sum = static_cast<double>(top[left]) + static_cast<double>(top[right]) +
                                           static_cast<double>(bottom[left]) + static_cast<double>(bottom[right]);
                        out[x * c + k] = static_cast<float>(0.25 * sum);
                    }
            }
        });
        return to;
    }
    const std::vector<BoxTaps> columns = box_taps(width, to.width), rows = box_taps(height, to.height);
    // Rows in parallel: a 4096² image's first level is 4 million texels.
    tbb::parallel_for(tbb::blocked_range<int>(0, to.height, 16), [&](const tbb::blocked_range<int>& range) {
        for (int y = range.begin(); y < range.end(); ++y) {
            const BoxTaps& ry = rows[static_cast<std::size_t>(y)];
            for (int x = 0; x < to.width; ++x) {
                const BoxTaps& rx = columns[static_cast<std::size_t>(x)];
                // In double, so that the level is the box average rounded once.
                std::array<double, 4> sum{};
                for (int b = 0; b < ry.count; ++b) {
                    const std::size_t row = static_cast<std::size_t>(ry.first + b) * static_cast<std::size_t>(width);
                    for (int a = 0; a < rx.count; ++a) {
                        const double w =
                            ry.weight[static_cast<std::size_t>(b)] * rx.weight[static_cast<std::size_t>(a)];
                        const float* p = from + (row + static_cast<std::size_t>(rx.first + a)) * c;
                        for (std::size_t k = 0; k < c; ++k) sum[k] += w * static_cast<double>(p[k]);
                    }
                }
                float* out = to.texels.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(to.width) +
                                                 static_cast<std::size_t>(x)) *
                                                    c;
                for (std::size_t k = 0; k < c; ++k) out[k] = static_cast<float>(sum[k]);
            }
        }
    });
    return to;
}

// Level `level` (0 = the texture's own texels) read bilinearly at uv.
Rgba eval_level(const Texture& t, std::size_t level, Vec2 uv, TextureWrap wrap_u, TextureWrap wrap_v) {
    if (level == 0) return eval_texture(t, uv, wrap_u, wrap_v);
    const TextureLevel& l = t.mip_levels[level - 1];
    return eval_texels(l.texels.data(), l.width, l.height, t.channels, uv, wrap_u, wrap_v);
}

}  // namespace

void build_mip_pyramid(Texture& t) {
    t.mip_levels.clear();
    const float* from = t.texels.data();
    int width = t.width, height = t.height;
    while (width >= 2 && height >= 2) {
        t.mip_levels.push_back(half_level(from, width, height, t.channels));
        from = t.mip_levels.back().texels.data();
        width = t.mip_levels.back().width;
        height = t.mip_levels.back().height;
    }
}

void build_mip_pyramids(std::vector<Texture>& table) {
    tbb::parallel_for(std::size_t{0}, table.size(), [&table](std::size_t i) { build_mip_pyramid(table[i]); });
}

float mip_lod(const Texture& t, float uv_footprint) {
    return std::log2(uv_footprint * std::sqrt(static_cast<float>(t.width) * static_cast<float>(t.height)));
}

Rgba eval_texture_lod(const Texture& t, Vec2 uv, float lod, TextureWrap wrap_u, TextureWrap wrap_v) {
    if (!(lod > 0.0f) || t.mip_levels.empty()) return eval_texture(t, uv, wrap_u, wrap_v);
    const std::size_t coarsest = t.mip_levels.size();
    if (lod >= static_cast<float>(coarsest)) return eval_level(t, coarsest, uv, wrap_u, wrap_v);
    const auto fine = static_cast<std::size_t>(lod);
    const float f = lod - static_cast<float>(fine);
    const Rgba a = eval_level(t, fine, uv, wrap_u, wrap_v), b = eval_level(t, fine + 1, uv, wrap_u, wrap_v);
    Rgba out;
    for (std::size_t k = 0; k < 4; ++k) out[k] = (1.0f - f) * a[k] + f * b[k];
    return out;
}

}  // namespace sombra
