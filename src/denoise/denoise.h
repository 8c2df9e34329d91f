// The denoiser (spec §25): NFOR (Bitterli et al. 2016), non-linearly
// weighted first-order regression over the render's features, with
// half-buffer cross-filtering and a per-pixel choice between two
// bandwidths, then a second regression pass. Every output pixel is
// max(0, Σ w·c) over the half-buffer colours c of its neighbourhood, and
// explain_denoised_pixel gives those weights.
#pragma once

#include <array>
#include <atomic>
#include <vector>

#include "denoise/denoise_layers.h"
#include "denoise/raster.h"

namespace sombra {

// Where a denoise_image call spent its time, in seconds (a benchmark's view).
struct DenoiseTimes {
    double features = 0;     // the features' cross-filtering
    double regression = 0;   // the first pass: two bandwidths × two halves
    double selection = 0;    // the error estimates and the choice between bandwidths
    double second_pass = 0;  // the features filtered again and the second regression
};

// The denoised image, 3 floats a pixel, row-major, top row first: a pure
// function of `layers`, the same bytes for any `threads` (0 = all).
// `layers` must pass check_denoise_layers. Once `*cancel` is true (looked
// at before each tile of kDenoiseTile² pixels) it stops and returns an
// empty vector: a viewer or Python's Ctrl-C need not wait for the end.
// `times`, when given, gets the seconds each stage took.
std::vector<float> denoise_image(const DenoiseLayers& layers, int threads = 0,
                                 const std::atomic<bool>* cancel = nullptr, DenoiseTimes* times = nullptr);

// How far the denoiser reads: a pixel of denoise_image(layers) rests on
// the layers' pixels within denoise_reach() of it along x and y alone
// (spec §27's --crop; docs/cli.md gives the figure). Its tiles and grid of
// windows start at the image's corner, so a window of the image denoised
// alone matches the whole image only if its corner is a multiple of
// kDenoiseAlign pixels from the image's.
int denoise_reach();
inline constexpr int kDenoiseAlign = 2 * kDenoiseTile;  // tiles run in a 2 × 2 checkerboard

// The window of a width × height image whose layers, denoised alone, give
// the pixels of `kept` bit for bit as denoising the whole image does:
// `kept` grown by denoise_reach() within the image, its corner moved back
// to a multiple of kDenoiseAlign.
PixelRect denoise_source_rect(PixelRect kept, int width, int height);

// The seconds denoise_image is expected to take on a width × height image
// with `threads` (0 = all hardware threads): what a --time budget keeps
// back for it (spec §25). From a measured cost per pixel (docs/performance.md).
double denoise_seconds_estimate(int width, int height, int threads);

// One term of a denoised pixel: half `half` (0: A, 1: B) of pixel (x, y),
// with the colour `raw` that its per-channel `weight` multiplies.
struct DenoiseTerm {
    int x = 0, y = 0;
    int half = 0;
    std::array<double, 3> weight{};
    std::array<float, 3> raw{};
};

struct DenoisedPixel {
    std::array<float, 3> value{};       // the pixel as denoise_image gives it
    std::array<double, 3> unclamped{};  // Σ weight·raw per channel, before max(0, ·)
    std::array<bool, 3> clamped{};      // where max(0, ·) changed it
    std::vector<DenoiseTerm> terms;     // every term with a nonzero weight, by row, column and half
};

// Pixel (x, y) of denoise_image(layers) with the weights the denoiser used
// to make it: per channel they add up to 1 and Σ weight·raw is the value
// before clamping (to float rounding).
DenoisedPixel explain_denoised_pixel(const DenoiseLayers& layers, int x, int y, int threads = 0);

}  // namespace sombra
