#include "render/accumulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sombra {

namespace {

void add3(std::vector<float>& sums, std::size_t pixel, Vec3 v) {
    float* p = &sums[3 * pixel];
    p[0] += v.x;
    p[1] += v.y;
    p[2] += v.z;
}

// Each pixel's 3-float sum divided by its sample count (a pixel with none,
// after a cancelled render, stays 0).
void divide_by_count(std::vector<float>& sums, const std::vector<std::uint32_t>& count) {
    for (std::size_t p = 0; p < count.size(); ++p) {
        if (count[p] == 0) continue;
        const Vec3 mean = Vec3{sums[3 * p], sums[3 * p + 1], sums[3 * p + 2]} / static_cast<float>(count[p]);
        sums[3 * p] = mean.x;
        sums[3 * p + 1] = mean.y;
        sums[3 * p + 2] = mean.z;
    }
}

std::vector<float> mean3(std::vector<float> sums, const std::vector<std::uint32_t>& count) {
    divide_by_count(sums, count);
    return sums;
}

}  // namespace

Accumulation::Accumulation(int width, int height, bool moments, AovSet aovs)
    : width_(width), height_(height), aovs_(aovs) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    rgb_sum_.assign(3 * n, 0.0f);
    count_.assign(n, 0);
    done_.assign(n, 0);
    if (moments) {
        luminance_sum_.assign(n, 0.0);
        luminance_squares_.assign(n, 0.0);
    }
    if (aovs.albedo) albedo_sum_.assign(3 * n, 0.0f);
    if (aovs.normal) normal_sum_.assign(3 * n, 0.0f);
    if (aovs.position) position_sum_.assign(3 * n, 0.0f);
    if (aovs.depth) {
        depth_sum_.assign(n, 0.0f);
        hits_.assign(n, 0);
    }
    if (aovs.variance || aovs.denoise) {
        channel_sum_.assign(3 * n, 0.0);
        channel_squares_.assign(3 * n, 0.0);
    }
    if (aovs.denoise) {
        for (int h = 0; h < 2; ++h) {
            half_rgb_[h].assign(3 * n, 0.0f);
            half_albedo_[h].assign(3 * n, 0.0f);
            half_normal_[h].assign(3 * n, 0.0f);
            half_depth_[h].assign(n, 0.0f);
            half_hits_[h].assign(n, 0);
        }
    }
}

void Accumulation::add(std::size_t pixel, Vec3 radiance, const FirstHit* first) {
    add3(rgb_sum_, pixel, radiance);
    const std::uint32_t index = count_[pixel]++;
    if (!half_rgb_[0].empty()) {
        const std::uint32_t h = index & 1u;
        add3(half_rgb_[h], pixel, radiance);
        if (first != nullptr && first->hit) {
            add3(half_albedo_[h], pixel, first->albedo);
            add3(half_normal_[h], pixel, first->normal);
            half_depth_[h][pixel] += first->depth;
            ++half_hits_[h][pixel];
        }
    }
    if (!luminance_sum_.empty()) {
        // Rec. 709 relative luminance (core/vec3.h), what §18's rule measures noise in.
        const double y = luminance(radiance);
        luminance_sum_[pixel] += y;
        luminance_squares_[pixel] += y * y;
    }
    if (!channel_sum_.empty()) {
        const double c[3] = {radiance.x, radiance.y, radiance.z};
        for (int k = 0; k < 3; ++k) {
            channel_sum_[3 * pixel + k] += c[k];
            channel_squares_[3 * pixel + k] += c[k] * c[k];
        }
    }
    if (first == nullptr || !first->hit) return;  // a miss adds 0 to every AOV
    if (!albedo_sum_.empty()) add3(albedo_sum_, pixel, first->albedo);
    if (!normal_sum_.empty()) add3(normal_sum_, pixel, first->normal);
    if (!position_sum_.empty()) add3(position_sum_, pixel, first->position);
    if (!depth_sum_.empty()) {
        depth_sum_[pixel] += first->depth;
        ++hits_[pixel];
    }
}

double Accumulation::luminance_mean(std::size_t pixel) const {
    return luminance_sum_[pixel] / static_cast<double>(count_[pixel]);
}

double Accumulation::luminance_standard_error(int i, int j) const {
    double relative_squares = 0, degrees_of_freedom = 0;
    for (int y = std::max(j - 1, 0); y <= std::min(j + 1, height_ - 1); ++y) {
        for (int x = std::max(i - 1, 0); x <= std::min(i + 1, width_ - 1); ++x) {
            const std::size_t q = index(x, y);
            const auto n = static_cast<double>(count_[q]);
            if (n < 2) continue;
            const double mean = luminance_sum_[q] / n;
            const double floor = std::max(mean, kLuminanceFloor);
            // max(): the rounding of a constant pixel's sums can go below 0.
            relative_squares += std::max(0.0, luminance_squares_[q] - n * mean * mean) / (floor * floor);
            degrees_of_freedom += n - 1.0;
        }
    }
    const std::size_t p = index(i, j);
    const double relative_variance = relative_squares / degrees_of_freedom;
    return std::max(luminance_mean(p), kLuminanceFloor) * std::sqrt(relative_variance / static_cast<double>(count_[p]));
}

Film Accumulation::take_image() {
    divide_by_count(rgb_sum_, count_);
    Film film;
    film.width = width_;
    film.height = height_;
    film.rgb = std::move(rgb_sum_);
    return film;
}

Film Accumulation::mean_image() const {
    Film film;
    film.width = width_;
    film.height = height_;
    film.rgb = mean3(rgb_sum_, count_);
    return film;
}

AovImages Accumulation::aov_images() const {
    AovImages out;
    if (aovs_.albedo) out.albedo = mean3(albedo_sum_, count_);
    if (aovs_.normal) out.normal = mean3(normal_sum_, count_);
    if (aovs_.position) out.position = mean3(position_sum_, count_);
    if (aovs_.depth) {
        out.depth.resize(count_.size());
        for (std::size_t p = 0; p < count_.size(); ++p)
            out.depth[p] =
                hits_[p] > 0 ? depth_sum_[p] / static_cast<float>(hits_[p]) : std::numeric_limits<float>::infinity();
    }
    if (aovs_.spp) out.spp.assign(count_.begin(), count_.end());
    if (aovs_.variance) out.variance = variance_image();
    if (aovs_.denoise) out.denoise = denoise_layers();
    return out;
}

std::vector<float> Accumulation::variance_image() const {
    std::vector<float> variance(3 * count_.size());
    for (std::size_t p = 0; p < count_.size(); ++p) {
        const auto n = static_cast<double>(count_[p]);
        for (std::size_t k = 3 * p; k < 3 * p + 3; ++k) {
            if (n < 2) {
                variance[k] = std::numeric_limits<float>::infinity();
                continue;
            }
            const double mean = channel_sum_[k] / n;
            // max(): rounding can take a constant pixel's sum of squares just below n·m².
            const double sample_variance = std::max(0.0, channel_squares_[k] - n * mean * mean) / (n - 1.0);
            variance[k] = static_cast<float>(sample_variance / n);
        }
    }
    return variance;
}

DenoiseLayers Accumulation::denoise_layers() const {
    DenoiseLayers layers;
    layers.width = width_;
    layers.height = height_;
    layers.variance = variance_image();
    const std::size_t n = count_.size();
    for (int h = 0; h < 2; ++h) {
        std::vector<std::uint32_t> half_count(n);
        // Sample k goes to half k mod 2: A holds ⌈n/2⌉ of n samples, B ⌊n/2⌋.
        for (std::size_t p = 0; p < n; ++p) half_count[p] = (count_[p] + (h == 0 ? 1u : 0u)) / 2;
        layers.color[h] = mean3(half_rgb_[h], half_count);
        layers.albedo[h] = mean3(half_albedo_[h], half_count);
        layers.normal[h] = mean3(half_normal_[h], half_count);
        layers.depth[h].resize(n);
        for (std::size_t p = 0; p < n; ++p)
            layers.depth[h][p] = half_hits_[h][p] > 0 ? half_depth_[h][p] / static_cast<float>(half_hits_[h][p])
                                                      : std::numeric_limits<float>::infinity();
    }
    // A pixel of one sample has nothing in half B: it takes A's values.
    for (std::size_t p = 0; p < n; ++p) {
        if (count_[p] != 1) continue;
        for (std::size_t k = 3 * p; k < 3 * p + 3; ++k) {
            layers.color[1][k] = layers.color[0][k];
            layers.albedo[1][k] = layers.albedo[0][k];
            layers.normal[1][k] = layers.normal[0][k];
        }
        layers.depth[1][p] = layers.depth[0][p];
    }
    return layers;
}

}  // namespace sombra
