#include "denoise/nl_means.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sombra {

namespace {

// Keeps a zero-variance (noise-free) guide's distances finite: equal
// values are then at distance 0, different ones very far.
constexpr float kVarianceFloor = 1e-10f;

}  // namespace

void nl_means_tile_weights(const Raster& guide, const Raster& guide_variance, PixelRect centres,
                           const NlMeansParams& params, std::vector<float>& weights, std::vector<float>& scratch) {
    const int radius = params.window_radius, patch = params.patch_radius;
    const int side = window_side(params);
    const int tw = centres.width(), th = centres.height();
    const std::size_t n = static_cast<std::size_t>(tw) * static_cast<std::size_t>(th);
    weights.assign(static_cast<std::size_t>(window_offsets(params)) * n, 0.0f);
    // The centres grown by the patch radius: the pixels a patch may cover.
    const PixelRect grown{std::max(centres.x0 - patch, 0), std::max(centres.y0 - patch, 0),
                          std::min(centres.x1 + patch, guide.width), std::min(centres.y1 + patch, guide.height)};
    const int gw = grown.width(), gh = grown.height();
    const std::size_t grown_n = static_cast<std::size_t>(gw) * static_cast<std::size_t>(gh);
    // Per grown pixel: distance and whether it counts; then the row sums over the patch.
    scratch.assign(2 * grown_n + 2 * static_cast<std::size_t>(gh) * static_cast<std::size_t>(tw), 0.0f);
    float* distance = scratch.data();
    float* valid = distance + grown_n;
    float* row_distance = valid + grown_n;
    float* row_valid = row_distance + static_cast<std::size_t>(gh) * static_cast<std::size_t>(tw);
    const int channels = guide.channels;
    const float k2 = params.k * params.k;
    const float per_channel = 1.0f / static_cast<float>(channels);

    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            // The pixel distance between x and x + (dx, dy) over the grown rectangle.
            for (int y = grown.y0; y < grown.y1; ++y) {
                const int qy = y + dy;
                float* d_row = distance + static_cast<std::size_t>(y - grown.y0) * static_cast<std::size_t>(gw);
                float* v_row = valid + static_cast<std::size_t>(y - grown.y0) * static_cast<std::size_t>(gw);
                for (int x = grown.x0; x < grown.x1; ++x) {
                    const int qx = x + dx;
                    if (qy < 0 || qy >= guide.height || qx < 0 || qx >= guide.width) {
                        d_row[x - grown.x0] = 0.0f;
                        v_row[x - grown.x0] = 0.0f;
                        continue;
                    }
                    const float* gp = guide.at(x, y);
                    const float* gq = guide.at(qx, qy);
                    const float* vp = guide_variance.at(x, y);
                    const float* vq = guide_variance.at(qx, qy);
                    float sum = 0.0f;
                    for (int c = 0; c < channels; ++c) {
                        const float diff = gp[c] - gq[c];
                        // The expected squared difference of two noisy values is
                        // subtracted, so that alike patches come out near 0.
                        const float noise = vp[c] + std::min(vp[c], vq[c]);
                        sum += (diff * diff - noise) / (kVarianceFloor + k2 * (vp[c] + vq[c]));
                    }
                    d_row[x - grown.x0] = sum * per_channel;
                    v_row[x - grown.x0] = 1.0f;
                }
            }
            // Patch sums: along rows, then down columns.
            for (int y = 0; y < gh; ++y) {
                const float* d_row = distance + static_cast<std::size_t>(y) * static_cast<std::size_t>(gw);
                const float* v_row = valid + static_cast<std::size_t>(y) * static_cast<std::size_t>(gw);
                float* out_d = row_distance + static_cast<std::size_t>(y) * static_cast<std::size_t>(tw);
                float* out_v = row_valid + static_cast<std::size_t>(y) * static_cast<std::size_t>(tw);
                for (int c = 0; c < tw; ++c) {
                    const int x = centres.x0 + c;
                    const int lo = std::max(x - patch, grown.x0) - grown.x0;
                    const int hi = std::min(x + patch, grown.x1 - 1) - grown.x0;
                    float sd = 0.0f, sv = 0.0f;
                    for (int i = lo; i <= hi; ++i) {
                        sd += d_row[i];
                        sv += v_row[i];
                    }
                    out_d[c] = sd;
                    out_v[c] = sv;
                }
            }
            float* out = weights.data() + static_cast<std::size_t>((dy + radius) * side + (dx + radius)) * n;
            for (int r = 0; r < th; ++r) {
                const int y = centres.y0 + r;
                if (y + dy < 0 || y + dy >= guide.height) continue;
                const int lo = std::max(y - patch, grown.y0) - grown.y0;
                const int hi = std::min(y + patch, grown.y1 - 1) - grown.y0;
                for (int c = 0; c < tw; ++c) {
                    const int x = centres.x0 + c;
                    if (x + dx < 0 || x + dx >= guide.width) continue;
                    float sd = 0.0f, sv = 0.0f;
                    for (int i = lo; i <= hi; ++i) {
                        sd += row_distance[static_cast<std::size_t>(i) * static_cast<std::size_t>(tw) +
                                           static_cast<std::size_t>(c)];
                        sv += row_valid[static_cast<std::size_t>(i) * static_cast<std::size_t>(tw) +
                                        static_cast<std::size_t>(c)];
                    }
                    // sv ≥ 1: the pair (p, q) itself is in the image.
                    out[static_cast<std::size_t>(r) * static_cast<std::size_t>(tw) + static_cast<std::size_t>(c)] =
                        std::exp(-std::max(0.0f, sd / sv));
                }
            }
        }
    }
}

Raster nl_means_filter(const Raster& values, const Raster& guide, const Raster& guide_variance,
                       const NlMeansParams& params, int threads, const std::atomic<bool>* cancel) {
    Raster out(values.width, values.height, values.channels);
    const int tiles_x = tile_count(values.width), tiles_y = tile_count(values.height);
    const int radius = params.window_radius, side = window_side(params);
    const int channels = values.channels;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int>& range) {
            std::vector<float> weights, scratch;
            for (int t = range.begin(); t < range.end(); ++t) {
                if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) return;
                const PixelRect tile = tile_rect(t % tiles_x, t / tiles_x, values.width, values.height);
                nl_means_tile_weights(guide, guide_variance, tile, params, weights, scratch);
                const std::size_t n = static_cast<std::size_t>(tile.width()) * static_cast<std::size_t>(tile.height());
                for (int y = tile.y0; y < tile.y1; ++y) {
                    for (int x = tile.x0; x < tile.x1; ++x) {
                        const std::size_t c =
                            static_cast<std::size_t>(y - tile.y0) * static_cast<std::size_t>(tile.width()) +
                            static_cast<std::size_t>(x - tile.x0);
                        float sum[4] = {0, 0, 0, 0};
                        float total = 0.0f;
                        for (int dy = -radius; dy <= radius; ++dy) {
                            if (y + dy < 0 || y + dy >= values.height) continue;
                            for (int dx = -radius; dx <= radius; ++dx) {
                                if (x + dx < 0 || x + dx >= values.width) continue;
                                const float w =
                                    weights[static_cast<std::size_t>((dy + radius) * side + (dx + radius)) * n + c];
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
