#include "denoise/nl_means.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "denoise/fast_exp.h"

namespace sombra {

namespace {

// Keeps a zero-variance (noise-free) guide's distances finite: equal
// values are then at distance 0, different ones very far.
constexpr float kVarianceFloor = 1e-10f;

// How many of the patch offsets s in [−patch, patch] keep both p + s and
// p + s + d inside [0, size): the patch pixels that count, along one axis.
int patch_span(int p, int d, int patch, int size) {
    const int lo = std::max({-patch, -p, -p - d});
    const int hi = std::min({patch, size - 1 - p, size - 1 - p - d});
    return std::max(0, hi - lo + 1);
}

}  // namespace

void nl_means_tile_weights(const Raster& guide, const Raster& guide_variance, PixelRect centres, int stride,
                           const NlMeansParams& params, std::vector<float>& weights, std::vector<float>& scratch) {
    const int radius = params.window_radius, patch = params.patch_radius;
    const int side = window_side(params);
    const int width = guide.width, height = guide.height, channels = guide.channels;
    const int tw = centres.width(), th = centres.height();
    const int nx = strided_count(tw, stride), ny = strided_count(th, stride);
    const std::size_t n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
    const auto offsets = static_cast<std::size_t>(window_offsets(params));
    weights.resize(offsets * n);
    // The pixels the patches of p and of q = p + d may cover, in planes of
    // one channel each (guide, then variance), padded with `patch` columns
    // and rows of zeros all round so that patch sums need no bounds.
    const int reach = patch + radius;
    const int rx0 = centres.x0 - reach, ry0 = centres.y0 - reach;
    const int rw = tw + 2 * reach, rh = th + 2 * reach;
    const std::size_t plane = static_cast<std::size_t>(rw) * static_cast<std::size_t>(rh);
    // Distances over the centres grown by the patch radius, padded by it again.
    const int dw = tw + 4 * patch, dh = th + 4 * patch;
    const std::size_t distance_n = static_cast<std::size_t>(dw) * static_cast<std::size_t>(dh);
    const std::size_t rows_n = static_cast<std::size_t>(dh) * static_cast<std::size_t>(tw);
    // The weights are made offset by offset (offset-major), then transposed.
    scratch.assign(2 * plane * static_cast<std::size_t>(channels) + distance_n + rows_n +
                       2 * static_cast<std::size_t>(tw) + offsets * n,
                   0.0f);
    float* planes = scratch.data();
    float* distance = planes + 2 * plane * static_cast<std::size_t>(channels);
    float* row_sums = distance + distance_n;
    float* inverse_span_x = row_sums + rows_n;
    float* column_sum = inverse_span_x + tw;
    float* by_offset = column_sum + tw;
    const auto at = [rw](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(rw) + static_cast<std::size_t>(x);
    };
    for (int y = std::max(ry0, 0); y < std::min(ry0 + rh, height); ++y)
        for (int x = std::max(rx0, 0); x < std::min(rx0 + rw, width); ++x) {
            const float* g = guide.at(x, y);
            const float* v = guide_variance.at(x, y);
            for (int c = 0; c < channels; ++c) {
                planes[2 * plane * static_cast<std::size_t>(c) + at(x - rx0, y - ry0)] = g[c];
                planes[(2 * static_cast<std::size_t>(c) + 1) * plane + at(x - rx0, y - ry0)] = v[c];
            }
        }
    const float k2 = params.k * params.k;
    const float per_channel = 1.0f / static_cast<float>(channels);

    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            // The pixel distance between x and x + d where both are in the
            // image, 0 elsewhere (then it does not count: patch_span).
            std::fill(distance, distance + distance_n, 0.0f);
            const int gx0 = std::max({centres.x0 - patch, 0, -dx});
            const int gx1 = std::min({centres.x1 + patch, width, width - dx});
            for (int y = std::max({centres.y0 - patch, 0, -dy});
                 y < std::min({centres.y1 + patch, height, height - dy}); ++y) {
                float* out =
                    distance + static_cast<std::size_t>(y - centres.y0 + 2 * patch) * static_cast<std::size_t>(dw);
                for (int c = 0; c < channels; ++c) {
                    const float* g = planes + 2 * plane * static_cast<std::size_t>(c);
                    const float* v = g + plane;
                    const std::size_t p0 = at(gx0 - rx0, y - ry0), q0 = at(gx0 + dx - rx0, y + dy - ry0);
                    const float* __restrict gp = g + p0;
                    const float* __restrict gq = g + q0;
                    const float* __restrict vp = v + p0;
                    const float* __restrict vq = v + q0;
                    float* __restrict sum = out + (gx0 - centres.x0 + 2 * patch);
                    for (int i = 0; i < gx1 - gx0; ++i) {
                        const float diff = gp[i] - gq[i];
                        // The expected squared difference of two noisy values is
                        // subtracted, so that alike patches come out near 0.
                        const float noise = vp[i] + std::min(vp[i], vq[i]);
                        sum[i] += (diff * diff - noise) / (kVarianceFloor + k2 * (vp[i] + vq[i])) * per_channel;
                    }
                }
            }
            // Patch sums along rows, then down columns; the zeros add nothing.
            for (int r = patch; r < dh - patch; ++r) {
                const float* __restrict in =
                    distance + static_cast<std::size_t>(r) * static_cast<std::size_t>(dw) + patch;
                float* __restrict out = row_sums + static_cast<std::size_t>(r) * static_cast<std::size_t>(tw);
                for (int c = 0; c < tw; ++c) out[c] = 0.0f;
                for (int s = -patch; s <= patch; ++s)
                    for (int c = 0; c < tw; ++c) out[c] += in[c + patch + s];
            }
            float* out = by_offset + static_cast<std::size_t>((dy + radius) * side + (dx + radius)) * n;
            for (int c = 0; c < tw; ++c) {
                // 1 / the patch pixels that count along x; 0 where q is outside the image.
                const int x = centres.x0 + c;
                const int span = patch_span(x, dx, patch, width);
                inverse_span_x[static_cast<std::size_t>(c)] =
                    x + dx >= 0 && x + dx < width ? 1.0f / static_cast<float>(std::max(span, 1)) : 0.0f;
            }
            for (int j = 0; j < ny; ++j) {
                const int r = j * stride, y = centres.y0 + r;
                if (y + dy < 0 || y + dy >= height) continue;
                const float inverse_span_y = 1.0f / static_cast<float>(std::max(patch_span(y, dy, patch, height), 1));
                float* __restrict sum = column_sum;
                for (int c = 0; c < tw; ++c) sum[c] = 0.0f;
                for (int s = -patch; s <= patch; ++s) {
                    const float* __restrict in =
                        row_sums + static_cast<std::size_t>(r + patch + s + patch) * static_cast<std::size_t>(tw);
                    for (int c = 0; c < tw; ++c) sum[c] += in[c];
                }
                float* __restrict row = out + static_cast<std::size_t>(j) * static_cast<std::size_t>(nx);
                for (int i = 0; i < nx; ++i) {
                    const auto c = static_cast<std::size_t>(i) * static_cast<std::size_t>(stride);
                    const float scale = inverse_span_x[c] * inverse_span_y;
                    const float distance_mean = sum[c] * scale;
                    const float w = exp_negative(distance_mean > 0.0f ? distance_mean : 0.0f);
                    row[i] = scale > 0.0f ? w : 0.0f;
                }
            }
        }
    }
    // Offset-major to pixel-major, in blocks that stay in the cache.
    constexpr std::size_t kBlock = 16;
    for (std::size_t o0 = 0; o0 < offsets; o0 += kBlock)
        for (std::size_t c0 = 0; c0 < n; c0 += kBlock)
            for (std::size_t c = c0; c < std::min(c0 + kBlock, n); ++c)
                for (std::size_t o = o0; o < std::min(o0 + kBlock, offsets); ++o)
                    weights[c * offsets + o] = by_offset[o * n + c];
}

Raster nl_means_filter(const Raster& values, const Raster& guide, const Raster& guide_variance,
                       const NlMeansParams& params, int threads, const std::atomic<bool>* cancel) {
    Raster out(values.width, values.height, values.channels);
    const int tiles_x = tile_count(values.width), tiles_y = tile_count(values.height);
    const int radius = params.window_radius, side = window_side(params);
    const int channels = values.channels;
    if (channels > kMaxFilterChannels) throw std::invalid_argument("nl_means_filter: more than 9 channels");
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int>& range) {
            std::vector<float> weights, scratch;
            for (int t = range.begin(); t < range.end(); ++t) {
                if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) return;
                const PixelRect tile = tile_rect(t % tiles_x, t / tiles_x, values.width, values.height);
                nl_means_tile_weights(guide, guide_variance, tile, 1, params, weights, scratch);
                const auto offsets = static_cast<std::size_t>(window_offsets(params));
                for (int y = tile.y0; y < tile.y1; ++y) {
                    for (int x = tile.x0; x < tile.x1; ++x) {
                        const std::size_t c =
                            static_cast<std::size_t>(y - tile.y0) * static_cast<std::size_t>(tile.width()) +
                            static_cast<std::size_t>(x - tile.x0);
                        float sum[kMaxFilterChannels] = {};
                        float total = 0.0f;
                        for (int dy = -radius; dy <= radius; ++dy) {
                            if (y + dy < 0 || y + dy >= values.height) continue;
                            for (int dx = -radius; dx <= radius; ++dx) {
                                if (x + dx < 0 || x + dx >= values.width) continue;
                                const float w = weights[c * offsets +
                                                        static_cast<std::size_t>((dy + radius) * side + (dx + radius))];
                                const float* v = values.at(x + dx, y + dy);
                                for (int ch = 0; ch < channels; ++ch) sum[ch] += w * v[ch];
                                total += w;
                            }
                        }
                        // total ≥ 1: a pixel's weight against itself is 1.
                        float* o = out.at(x, y);
                        for (int ch = 0; ch < channels; ++ch) o[ch] = sum[ch] / total;
                    }
                }
            }
        });
    });
    return out;
}

}  // namespace sombra
