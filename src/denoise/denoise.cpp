#include "denoise/denoise.h"

#include <tbb/info.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>

#include "denoise/nl_means.h"
#include "denoise/raster.h"
#include "denoise/regression.h"

namespace sombra {

namespace {

// NFOR's parameters (the paper's §5), tuned on this project's four test
// scenes (docs/performance.md, "The denoiser"): features cross-filtered
// over 9 × 9 windows with 5 × 5 patches; colour regressed over 15 × 15
// windows (the paper's 19 × 19 took 1.5× as long for no better images)
// with 5 × 5 patches in the first pass (the paper's 7 × 7 blurred more)
// and 7 × 7 in the second; the error estimates and the choice between
// candidates smoothed over 5 × 5 (over 7 × 7 the spheres' error was 17 %
// larger, over 3 × 3 the Cornell box's 44 %); the second pass's features
// over 5 × 5.
constexpr NlMeansParams kFeaturePrefilter{4, 2, 0.5f};
// The first pass's candidates, chosen between per pixel: the half as it
// is (kUnfiltered), and regressions with non-local-means bandwidths 0.4
// and 1. Where neither the features nor alike patches explain the colour
// (glass, a mirror's sky) the half's own noise is the smallest error.
constexpr float kUnfiltered = 0.0f;
constexpr float kBandwidths[] = {kUnfiltered, 0.4f, 1.0f};
constexpr int kCandidates = static_cast<int>(std::size(kBandwidths));
constexpr int kRegressionRadius = 7;
constexpr int kRegressionPatch = 2;
constexpr NlMeansParams kSelectionFilter{2, 1, 1.0f};
constexpr NlMeansParams kSecondFeatureFilter{2, 3, 0.5f};
constexpr NlMeansParams kSecondRegression{kRegressionRadius, 3, 1.0f};

// The feature groups, each filtered with its own weights: albedo, normal, depth.
struct FeatureGroup {
    int first, count;
};
constexpr FeatureGroup kFeatureGroups[3] = {{0, 3}, {3, 3}, {6, 1}};
// Depth enters as its logarithm: a difference is then relative, the same
// on a scene of any scale (the regression drops a feature whose spread
// over a window is below kFlatFeature). A half that hit nothing reads as
// a bit (×1.25) beyond the farthest surface within kMissDepthRadius of the
// pixel, or as log 1 = 0 with none there: a pixel's features, like all
// the denoiser reads, come from its neighbourhood alone (spec §27's crop).
constexpr int kMissDepthRadius = 8;
const float kMissDepthBeyond = std::log(1.25f);
// A variance the render could not estimate (+∞: one sample) reads as the
// largest finite one within kVarianceFillRadius of the pixel (0 with none).
constexpr int kVarianceFillRadius = 7;

// How far each stage reads around a pixel: non-local means reads values
// within the window and the guide within window + patch; a collaborative
// regression's output reads the guide up to 2R + P away (windows centred
// within R, each comparing patches up to R + P from its centre, as does
// the choice of an own window there) and the features and target up to 2R.
constexpr int filter_reach(const NlMeansParams& p) { return p.window_radius + p.patch_radius; }
constexpr int regression_reach(const NlMeansParams& p) { return 2 * p.window_radius + p.patch_radius; }
// The cross-filtered features: the miss fill, box3 of their variance, the prefilter.
constexpr int kFeatureReach = kMissDepthRadius + 1 + filter_reach(kFeaturePrefilter);
constexpr int kGuideReach = std::max(kVarianceFillRadius, kFeatureReach);
constexpr int kFirstReach = regression_reach({kRegressionRadius, kRegressionPatch, 1.0f}) + kGuideReach;
// The choice between candidates filters their errors, then the choice itself.
constexpr int kCombinedReach = 2 * filter_reach(kSelectionFilter) + kFirstReach;
constexpr int kSecondGuideReach = std::max(kCombinedReach, filter_reach(kSecondFeatureFilter) + kFeatureReach);
constexpr int kReach = regression_reach(kSecondRegression) + kSecondGuideReach;

Raster raster_of(const std::vector<float>& values, int width, int height, int channels) {
    Raster r(width, height, channels);
    r.values = values;
    return r;
}

Raster channels_of(const Raster& r, int first, int count) {
    Raster out(r.width, r.height, count);
    for (std::size_t p = 0; p < static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height); ++p)
        for (int c = 0; c < count; ++c)
            out.values[p * static_cast<std::size_t>(count) + static_cast<std::size_t>(c)] =
                r.values[p * static_cast<std::size_t>(r.channels) + static_cast<std::size_t>(first + c)];
    return out;
}

void put_channels(const Raster& part, int first, Raster& r) {
    for (std::size_t p = 0; p < static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height); ++p)
        for (int c = 0; c < part.channels; ++c)
            r.values[p * static_cast<std::size_t>(r.channels) + static_cast<std::size_t>(first + c)] =
                part.values[p * static_cast<std::size_t>(part.channels) + static_cast<std::size_t>(c)];
}

// Each value of `a` and `b` combined pointwise.
template <typename Combine>
Raster pointwise(const Raster& a, const Raster& b, Combine combine) {
    Raster out(a.width, a.height, a.channels);
    for (std::size_t i = 0; i < out.values.size(); ++i) out.values[i] = combine(a.values[i], b.values[i]);
    return out;
}

// The mean over the 3 × 3 pixels around each pixel (those in the image):
// steadies a variance estimated from two halves (one degree of freedom).
Raster box3(const Raster& r) {
    Raster out(r.width, r.height, r.channels);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            float* o = out.at(x, y);
            int n = 0;
            for (int v = std::max(y - 1, 0); v <= std::min(y + 1, r.height - 1); ++v)
                for (int u = std::max(x - 1, 0); u <= std::min(x + 1, r.width - 1); ++u, ++n)
                    for (int c = 0; c < r.channels; ++c) o[c] += r.at(u, v)[c];
            for (int c = 0; c < r.channels; ++c) o[c] /= static_cast<float>(n);
        }
    return out;
}

// Filters each feature group of `values` with weights from the same group of `guide`.
Raster filter_features(const Raster& values, const Raster& guide, const Raster& variance, const NlMeansParams& params,
                       int threads, const std::atomic<bool>* cancel) {
    Raster out(values.width, values.height, values.channels);
    for (const FeatureGroup& group : kFeatureGroups)
        put_channels(nl_means_filter(channels_of(values, group.first, group.count),
                                     channels_of(guide, group.first, group.count),
                                     channels_of(variance, group.first, group.count), params, threads, cancel),
                     group.first, out);
    return out;
}

// Per pixel, the largest of `values` within `radius` in x and y (a
// separable max filter: the result is exact in any order).
std::vector<float> local_max(const std::vector<float>& values, int width, int height, int radius) {
    std::vector<float> rows(values.size()), out(values.size());
    const auto at = [width](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float m = values[at(x, y)];
            for (int u = std::max(x - radius, 0); u <= std::min(x + radius, width - 1); ++u)
                m = std::max(m, values[at(u, y)]);
            rows[at(x, y)] = m;
        }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float m = rows[at(x, y)];
            for (int v = std::max(y - radius, 0); v <= std::min(y + radius, height - 1); ++v)
                m = std::max(m, rows[at(x, v)]);
            out[at(x, y)] = m;
        }
    return out;
}

// Each half's depth feature: log depth, a miss filled as kMissDepthRadius says.
std::array<std::vector<float>, 2> depth_features(const DenoiseLayers& layers) {
    constexpr float kNone = -std::numeric_limits<float>::infinity();
    const std::size_t n = static_cast<std::size_t>(layers.width) * static_cast<std::size_t>(layers.height);
    std::array<std::vector<float>, 2> out{std::vector<float>(n), std::vector<float>(n)};
    std::vector<float> farthest(n, kNone);
    for (int h = 0; h < 2; ++h)
        for (std::size_t p = 0; p < n; ++p) {
            const float depth = layers.depth[h][p];
            out[h][p] = std::isfinite(depth) ? std::log(std::max(depth, std::numeric_limits<float>::min())) : kNone;
            farthest[p] = std::max(farthest[p], out[h][p]);
        }
    farthest = local_max(farthest, layers.width, layers.height, kMissDepthRadius);
    for (int h = 0; h < 2; ++h)
        for (std::size_t p = 0; p < n; ++p)
            if (out[h][p] == kNone) out[h][p] = farthest[p] == kNone ? 0.0f : farthest[p] + kMissDepthBeyond;
    return out;
}

// The variance of a half's mean: twice the whole mean's (halves of equal
// size), an unknown one filled as kVarianceFillRadius says.
Raster half_variance_of(const DenoiseLayers& layers) {
    const std::size_t n = static_cast<std::size_t>(layers.width) * static_cast<std::size_t>(layers.height);
    std::vector<float> largest(n, 0.0f);
    for (std::size_t p = 0; p < n; ++p)
        for (std::size_t c = 0; c < 3; ++c)
            if (const float v = layers.variance[3 * p + c]; std::isfinite(v)) largest[p] = std::max(largest[p], v);
    largest = local_max(largest, layers.width, layers.height, kVarianceFillRadius);
    Raster out(layers.width, layers.height, 3);
    for (std::size_t i = 0; i < layers.variance.size(); ++i)
        out.values[i] = 2.0f * (std::isfinite(layers.variance[i]) ? layers.variance[i] : largest[i / 3]);
    return out;
}

// The features of half h: albedo, normal, and `depth` (depth_features').
Raster half_features(const DenoiseLayers& layers, int h, const std::vector<float>& depth) {
    Raster f(layers.width, layers.height, kRegressionFeatures);
    for (std::size_t p = 0; p < static_cast<std::size_t>(layers.width) * static_cast<std::size_t>(layers.height); ++p) {
        float* out = &f.values[p * kRegressionFeatures];
        for (int c = 0; c < 3; ++c) {
            out[c] = layers.albedo[h][3 * p + static_cast<std::size_t>(c)];
            out[3 + c] = layers.normal[h][3 * p + static_cast<std::size_t>(c)];
        }
        out[6] = depth[p];
    }
    return f;
}

// The albedo below which a surface counts as black (or as no surface):
// demodulated leaves such a pixel's colour as it is.
constexpr float kAlbedoFloor = 0.01f;

// The guide non-local means compares patches in: the colour divided by the
// first surface's albedo (its variance by the albedo squared), so that a
// texture the regression's features explain anyway does not make alike
// patches look different and leave a pixel, a firefly above all, alone.
struct Guide {
    Raster color, variance;
};
Guide demodulated(const Raster& color, const Raster& variance, const Raster& features) {
    Guide g{Raster(color.width, color.height, 3), Raster(color.width, color.height, 3)};
    for (std::size_t p = 0; p < static_cast<std::size_t>(color.width) * static_cast<std::size_t>(color.height); ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const float albedo = features.values[p * kRegressionFeatures + c];
            const float scale = albedo > kAlbedoFloor ? 1.0f / albedo : 1.0f;
            g.color.values[3 * p + c] = color.values[3 * p + c] * scale;
            g.variance.values[3 * p + c] = variance.values[3 * p + c] * scale * scale;
        }
    return g;
}

// Everything the forward pass makes that the weights of a pixel need.
struct NforPasses {
    Raster color[2];                         // the halves
    Raster half_variance;                    // the variance of a half's mean
    Raster features[2];                      // each half's features, cross-filtered
    Guide guide[2];                          // each half demodulated: the guide of the other half's regression
    RegressionResult first[kCandidates][2];  // [bandwidth][half]
    Raster selection[kCandidates];           // per pixel and channel, each bandwidth's share (adding up to 1)
    Raster combined, combined_variance, final_features;
    Guide second_guide;
    RegressionResult second;
};

using Clock = std::chrono::steady_clock;

// Seconds since `start`, which moves to now.
double lap(Clock::time_point& start) {
    const Clock::time_point now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - start).count();
    start = now;
    return seconds;
}

// Drops an image no later step reads, so that a large frame's peak stays low.
void release(Raster& r) { r = Raster(); }

// Which of the passes' images run_passes keeps: explain's backward run reads
// the weights' inputs of every step; the image alone needs none of them.
enum class Keep { Image, ForExplain };

// The first pass's candidates per pixel and channel, each one's share of
// the result (adding up to 1): the smallest error estimate, smoothed.
void choose_candidates(NforPasses& s, const Guide& mean_guide, int threads, const std::atomic<bool>* cancel) {
    const int w = s.color[0].width, h = s.color[0].height;
    // Each half's filtered value against the other half's noisy one, less
    // that half's variance, estimates the error (the paper's §5.3); the
    // candidates' estimates side by side, filtered with one set of weights.
    // Value i of a 3-channel image (pixel i / 3, channel i % 3) in the
    // candidates' images side by side: candidate k's is at slot(i) + 3·k.
    const auto slot = [](std::size_t i) { return kCandidates * (i - i % 3) + i % 3; };
    Raster noisy_mse(w, h, 3 * kCandidates);
    for (std::size_t i = 0; i < s.color[0].values.size(); ++i) {
        const float a = s.color[0].values[i], b = s.color[1].values[i];
        for (std::size_t k = 0; k < kCandidates; ++k) {
            const float fa = s.first[k][0].value.values[i], fb = s.first[k][1].value.values[i];
            const float mse_a = (b - fa) * (b - fa) - s.half_variance.values[i];
            const float mse_b = (a - fb) * (a - fb) - s.half_variance.values[i];
            noisy_mse.values[slot(i) + 3 * k] = 0.5f * (mse_a + mse_b) - 0.25f * (fb - fa) * (fb - fa);
        }
    }
    const Raster mse =
        nl_means_filter(noisy_mse, mean_guide.color, mean_guide.variance, kSelectionFilter, threads, cancel);
    release(noisy_mse);
    // The best candidate per pixel and channel as indicators (the last one's
    // is 1 less the others'), smoothed so that the choice blends.
    Raster choice(w, h, 3 * (kCandidates - 1));
    for (std::size_t i = 0; i < s.color[0].values.size(); ++i) {
        std::size_t best = 0;
        for (std::size_t k = 1; k < kCandidates; ++k)
            if (!(mse.values[slot(i) + 3 * best] < mse.values[slot(i) + 3 * k])) best = k;
        if (best + 1 < kCandidates) choice.values[(kCandidates - 1) * (i - i % 3) + i % 3 + 3 * best] = 1.0f;
    }
    const Raster shares =
        nl_means_filter(choice, mean_guide.color, mean_guide.variance, kSelectionFilter, threads, cancel);
    for (int k = 0; k < kCandidates; ++k) s.selection[k] = Raster(w, h, 3);
    for (std::size_t i = 0; i < s.color[0].values.size(); ++i) {
        float rest = 1.0f;
        for (std::size_t k = 0; k + 1 < kCandidates; ++k) {
            s.selection[k].values[i] = shares.values[(kCandidates - 1) * (i - i % 3) + i % 3 + 3 * k];
            rest -= s.selection[k].values[i];
        }
        s.selection[kCandidates - 1].values[i] = rest;
    }
}

// Under `cancel`, once it is true the passes stop at the end of the stage
// under way (a stage's filters skip their remaining tiles): their values
// are then unfinished.
NforPasses run_passes(const DenoiseLayers& layers, int threads, const std::atomic<bool>* cancel, DenoiseTimes& times,
                      Keep keep) {
    const auto cancelled = [cancel] { return cancel != nullptr && cancel->load(); };
    Clock::time_point start = Clock::now();
    const int w = layers.width, h = layers.height;
    NforPasses s;
    for (int half = 0; half < 2; ++half) s.color[half] = raster_of(layers.color[half], w, h, 3);
    s.half_variance = half_variance_of(layers);
    {
        const std::array<std::vector<float>, 2> depth = depth_features(layers);
        const Raster raw_features[2] = {half_features(layers, 0, depth[0]), half_features(layers, 1, depth[1])};
        const Raster feature_variance = box3(
            pointwise(raw_features[0], raw_features[1], [](float a, float b) { return 0.5f * (a - b) * (a - b); }));
        // Cross-filtering: each half's features, weighted by the other half's,
        // so that a half's noise does not choose its own weights.
        for (int half = 0; half < 2; ++half)
            s.features[half] = filter_features(raw_features[half], raw_features[1 - half], feature_variance,
                                               kFeaturePrefilter, threads, cancel);
    }
    times.features += lap(start);
    if (cancelled()) return s;

    for (int half = 0; half < 2; ++half) s.guide[half] = demodulated(s.color[half], s.half_variance, s.features[half]);
    Raster mean_features = pointwise(s.features[0], s.features[1], [](float a, float b) { return 0.5f * (a + b); });
    for (int k = 0; k < kCandidates; ++k) {
        const NlMeansParams params{kRegressionRadius, kRegressionPatch, kBandwidths[k]};
        for (int half = 0; half < 2; ++half)
            if (kBandwidths[k] == kUnfiltered)
                s.first[k][half].value = s.color[half];
            else
                s.first[k][half] =
                    collaborative_regression(s.color[half], s.guide[1 - half].color, s.guide[1 - half].variance,
                                             s.features[1 - half], params, threads, cancel);
    }
    if (keep == Keep::Image)
        for (Guide& g : s.guide) release(g.color), release(g.variance);
    times.regression += lap(start);
    if (cancelled()) return s;
    {
        const Raster mean_color = pointwise(s.color[0], s.color[1], [](float a, float b) { return 0.5f * (a + b); });
        const Raster variance = pointwise(s.half_variance, s.half_variance, [](float v, float) { return 0.5f * v; });
        choose_candidates(s, demodulated(mean_color, variance, mean_features), threads, cancel);
    }
    times.selection += lap(start);
    if (cancelled()) return s;

    Raster result[2];
    for (int half = 0; half < 2; ++half) {
        result[half] = Raster(w, h, 3);
        for (std::size_t i = 0; i < result[half].values.size(); ++i)
            for (int k = 0; k < kCandidates; ++k)
                result[half].values[i] += s.selection[k].values[i] * s.first[k][half].value.values[i];
    }
    if (keep == Keep::Image) {
        for (auto& candidate : s.first)
            for (RegressionResult& r : candidate) r = RegressionResult{};
        for (Raster& r : s.selection) release(r);
    }
    // The second pass: the halves' results together, with their difference
    // as the noise left, regressed on features filtered once more.
    {
        const Raster features_variance =
            pointwise(s.features[0], s.features[1], [](float a, float b) { return 0.25f * (a - b) * (a - b); });
        s.final_features =
            filter_features(mean_features, mean_features, features_variance, kSecondFeatureFilter, threads, cancel);
    }
    release(mean_features);
    if (keep == Keep::Image)
        for (Raster& r : s.features) release(r);
    s.combined = pointwise(result[0], result[1], [](float a, float b) { return 0.5f * (a + b); });
    s.combined_variance = pointwise(result[0], result[1], [](float a, float b) { return 0.25f * (a - b) * (a - b); });
    for (Raster& r : result) release(r);
    s.second_guide = demodulated(s.combined, s.combined_variance, s.final_features);
    s.second = collaborative_regression(s.combined, s.second_guide.color, s.second_guide.variance, s.final_features,
                                        kSecondRegression, threads, cancel);
    times.second_pass += lap(start);
    return s;
}

PixelRect grown(PixelRect r, int by, int width, int height) {
    return {std::max(r.x0 - by, 0), std::max(r.y0 - by, 0), std::min(r.x1 + by, width), std::min(r.y1 + by, height)};
}

}  // namespace

int denoise_reach() { return kReach; }

PixelRect denoise_source_rect(PixelRect kept, int width, int height) {
    const auto aligned_down = [](int v) { return std::max(v, 0) / kDenoiseAlign * kDenoiseAlign; };
    return {aligned_down(kept.x0 - kReach), aligned_down(kept.y0 - kReach), std::min(kept.x1 + kReach, width),
            std::min(kept.y1 + kReach, height)};
}

double denoise_seconds_estimate(int width, int height, int threads) {
    // One thread's seconds a pixel: 20–23 µs measured on a quiet 2-core
    // machine, and a margin (docs/performance.md, "The denoiser").
    constexpr double kSecondsPerPixel = 26e-6;
    const int available = threads > 0 ? threads : tbb::info::default_concurrency();
    // The tiles of one phase run side by side: no more threads than those help.
    const int tiles = std::max(1, tile_count(width) * tile_count(height) / 4);
    return kSecondsPerPixel * static_cast<double>(width) * static_cast<double>(height) /
           static_cast<double>(std::min(available, tiles));
}

std::vector<float> denoise_image(const DenoiseLayers& layers, int threads, const std::atomic<bool>* cancel,
                                 DenoiseTimes* times) {
    DenoiseTimes ignored;
    NforPasses passes = run_passes(layers, threads, cancel, times != nullptr ? *times : ignored, Keep::Image);
    if (cancel != nullptr && cancel->load()) return {};
    std::vector<float> out = std::move(passes.second.value.values);
    for (float& v : out) v = std::max(v, 0.0f);
    return out;
}

DenoisedPixel explain_denoised_pixel(const DenoiseLayers& layers, int x, int y, int threads) {
    DenoiseTimes times;
    const NforPasses s = run_passes(layers, threads, nullptr, times, Keep::ForExplain);
    const int w = layers.width, h = layers.height;
    // Backwards through the passes, the weights held as they were: the
    // second regression, the mean of the halves, the choice of bandwidth,
    // the first regressions.
    Raster g_out(w, h, 3);
    for (int c = 0; c < 3; ++c) g_out.at(x, y)[c] = 1.0f;
    const PixelRect pixel{x, y, x + 1, y + 1};
    Raster g_combined(w, h, 3);
    collaborative_regression_adjoint(s.second_guide.color, s.second_guide.variance, s.final_features, kSecondRegression,
                                     s.second, g_out, pixel, g_combined);
    const PixelRect combined_support = grown(pixel, 2 * kRegressionRadius, w, h);
    Raster g_half[2] = {Raster(w, h, 3), Raster(w, h, 3)};
    for (int k = 0; k < kCandidates; ++k) {
        const NlMeansParams params{kRegressionRadius, kRegressionPatch, kBandwidths[k]};
        Raster g_first(w, h, 3);
        for (std::size_t i = 0; i < g_first.values.size(); ++i)
            g_first.values[i] = 0.5f * g_combined.values[i] * s.selection[k].values[i];
        for (int half = 0; half < 2; ++half)
            if (kBandwidths[k] == kUnfiltered)
                for (std::size_t i = 0; i < g_first.values.size(); ++i) g_half[half].values[i] += g_first.values[i];
            else
                collaborative_regression_adjoint(s.guide[1 - half].color, s.guide[1 - half].variance,
                                                 s.features[1 - half], params, s.first[k][half], g_first,
                                                 combined_support, g_half[half]);
    }

    DenoisedPixel out;
    const float* value = s.second.value.at(x, y);
    const PixelRect support = grown(combined_support, 2 * kRegressionRadius, w, h);
    for (int qy = support.y0; qy < support.y1; ++qy)
        for (int qx = support.x0; qx < support.x1; ++qx)
            for (int half = 0; half < 2; ++half) {
                const float* g = g_half[half].at(qx, qy);
                if (g[0] == 0.0f && g[1] == 0.0f && g[2] == 0.0f) continue;
                DenoiseTerm term{qx, qy, half, {g[0], g[1], g[2]}, {}};
                const float* raw = s.color[half].at(qx, qy);
                for (int c = 0; c < 3; ++c) {
                    term.raw[c] = raw[c];
                    out.unclamped[c] += term.weight[c] * raw[c];
                }
                out.terms.push_back(term);
            }
    for (int c = 0; c < 3; ++c) {
        out.value[c] = std::max(value[c], 0.0f);
        out.clamped[c] = value[c] < 0.0f;
    }
    return out;
}

}  // namespace sombra
