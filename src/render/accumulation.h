// What a render's sample passes have gathered so far, pixel by pixel, and
// the images made from it at the end (spec §18): the radiance's mean, the
// adaptive stopping rule's luminance moments, the AOVs' sums and each
// pixel's sample count. Plain arrays, one entry per pixel; a pixel is only
// ever touched by the thread rendering it, its samples added in index order,
// so every sum is the same whatever the thread count.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "denoise/denoise_layers.h"
#include "render/aov_set.h"
#include "render/film.h"
#include "render/first_hit.h"

namespace sombra {

// The AOV images, each empty unless asked: albedo, normal and position 3
// floats a pixel (the mean over all the pixel's samples, a miss adding 0),
// depth and spp one (depth: the mean over the samples that hit, +∞ where
// none does; spp: the samples taken), variance 3 (per channel, the
// unbiased estimate s²/n of the variance of the pixel's mean from its own n
// samples; +∞ where n < 2, since one sample says nothing of its spread).
// With the denoise AOV, `denoise` holds the denoiser's layers: the means
// of each pixel's even- and odd-indexed samples (a half with no sample
// takes the other's), the variance, and the features per half.
struct AovImages {
    std::vector<float> albedo, normal, position, depth, spp, variance;
    DenoiseLayers denoise;
};

class Accumulation {
public:
    // `moments`: keep the luminance sums the adaptive rule needs.
    Accumulation(int width, int height, bool moments, AovSet aovs);

    std::size_t pixels() const { return count_.size(); }
    int width() const { return width_; }
    int height() const { return height_; }
    // Pixel (i, j)'s index in the arrays (row-major, top row first).
    std::size_t index(int i, int j) const {
        return static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(i);
    }
    std::uint32_t count(std::size_t pixel) const { return count_[pixel]; }
    bool done(std::size_t pixel) const { return done_[pixel] != 0; }
    void finish(std::size_t pixel) { done_[pixel] = 1; }

    // Adds one sample's radiance (and first hit, when AOVs are gathered) to
    // pixel `pixel`: the next sample in its index order.
    void add(std::size_t pixel, Vec3 radiance, const FirstHit* first);

    // The mean luminance of a pixel's samples so far.
    double luminance_mean(std::size_t pixel) const;
    // The estimated standard error of pixel (i, j)'s mean luminance from the
    // samples so far: its sample variance relative to its mean, pooled over
    // the pixel and its 8 neighbours (those with two samples or more; the
    // pixel itself must have two), times max(mean, kLuminanceFloor) / √n.
    //
    // Pooled, because a stopping rule that reads only the pixel's own
    // samples stops it on a lucky streak (a few samples that missed a rare
    // bright path: low mean and low variance together) and darkens the
    // image. Relative, so that a dark pixel beside a bright one is judged by
    // the neighbours' noise in proportion to their brightness.
    double luminance_standard_error(int i, int j) const;

    // The AOVs asked for, as described at AovImages.
    AovImages aov_images() const;
    // The image: each pixel's radiance sum divided by its sample count, in
    // place (a film-sized buffer less at the peak), so the radiance sums are
    // gone after it.
    Film take_image();
    // The same image as take_image would give now, as a copy: the sums stay
    // and further samples may be added (the viewer's image after each pass).
    Film mean_image() const;

    // §18's floor on the mean luminance the threshold scales with.
    static constexpr double kLuminanceFloor = 1e-3;

private:
    int width_ = 0, height_ = 0;
    AovSet aovs_;
    std::vector<float> rgb_sum_;  // 3 a pixel
    std::vector<std::uint32_t> count_;
    std::vector<std::uint8_t> done_;
    std::vector<double> luminance_sum_, luminance_squares_;      // only with moments
    std::vector<float> albedo_sum_, normal_sum_, position_sum_;  // 3 a pixel, when asked
    std::vector<float> depth_sum_;
    std::vector<std::uint32_t> hits_;  // samples whose camera ray hit a surface, with depth
    // With the variance AOV: each channel's sum and sum of squares, in
    // double so that s² = (Σx² − n·m²)/(n − 1) keeps its digits.
    std::vector<double> channel_sum_, channel_squares_;  // 3 a pixel
    // With the denoise AOV: the same sums split by the sample's index, even (0) and odd (1).
    std::array<std::vector<float>, 2> half_rgb_, half_albedo_, half_normal_, half_depth_;
    std::array<std::vector<std::uint32_t>, 2> half_hits_;

    std::vector<float> variance_image() const;
    DenoiseLayers denoise_layers() const;
};

}  // namespace sombra
