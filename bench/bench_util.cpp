#include "bench_util.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#ifdef SOMBRA_HAVE_EMBREE
#include "accel/embree_plugin.h"
#endif

namespace sombra::bench {

Accel make_compared_accel(const Scene& scene, AccelKind kind, const EmbreeSettings& embree) {
#ifdef SOMBRA_HAVE_EMBREE
    if (kind == AccelKind::Embree && (embree.quality == EmbreeQuality::High || embree.robust)) {
        Accel accel;
        accel.kind = kind;
        accel.mesh = &scene.geometry;
        accel.cutouts = make_cutouts(scene.geometry, scene.materials, scene.textures);
        accel.embree_api = &embree_plugin();  // as sombra render --accel embree reaches it
        accel.embree =
            accel.embree_api->make_scene(scene, accel.cutouts, embree.quality == EmbreeQuality::High, embree.robust);
        return accel;
    }
#endif
    return make_accel(scene, kind);
}

std::string accel_label(AccelKind kind, const EmbreeSettings& embree) {
    std::string label(accel_name(kind));
    if (kind == AccelKind::Bvh || kind == AccelKind::Brute) return label;
    if (embree.quality == EmbreeQuality::High) label += " high";
    if (embree.robust) label += " robust";
    return label;
}

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string fixed(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

std::string seconds(double s) {
    if (s >= 10) return fixed(s, 1);
    if (s >= 1) return fixed(s, 2);
    if (s >= 0.1) return fixed(s, 3);
    if (s >= 0.01) return fixed(s, 4);
    return fixed(s, 5);
}

std::string ratio(double a, double b) { return b > 0 ? fixed(a / b, 2) : "–"; }

std::string to_markdown(const Table& table) {
    auto line = [](const std::vector<std::string>& cells) {
        std::string text = "|";
        for (const std::string& cell : cells) text += " " + cell + " |";
        return text + "\n";
    };
    std::string out = line(table.header);
    std::vector<std::string> rule;
    for (std::size_t c = 0; c < table.header.size(); ++c) {
        rule.push_back(c < table.right.size() && table.right[c] ? "---:" : "---");
    }
    out += line(rule);
    for (const std::vector<std::string>& row : table.rows) out += line(row);
    return out;
}

std::vector<AccelKind> compared_accels() {
#ifdef SOMBRA_HAVE_EMBREE
    return {AccelKind::Bvh, AccelKind::Embree};
#else
    return {AccelKind::Bvh};
#endif
}

ImageAgreement compare_films(const Film& a, const Film& b) {
    ImageAgreement agreement;
    if (a.rgb.size() != b.rgb.size()) return agreement;
    agreement.pixels = a.rgb.size() / 3;
    for (std::size_t p = 0; p < agreement.pixels; ++p) {
        agreement.equal += same_colour(&a.rgb[3 * p], &b.rgb[3 * p]);
    }
    return agreement;
}

bool same_colour(const float* a, const float* b) {
    bool same = true;
    for (int c = 0; c < 3; ++c) {
        const float scale = std::max({std::fabs(a[c]), std::fabs(b[c]), 1e-2f});
        same = same && std::fabs(a[c] - b[c]) <= 1e-3f * scale;
    }
    return same;
}

ImageAgreement bvh_against_brute(const TriangleMesh& mesh, const Accel& bvh, int width, int height,
                                 double rays_per_pixel, std::size_t min_pixels,
                                 const std::function<Vec3(const Accel& accel, int i, int j)>& radiance) {
    constexpr double kBruteBudget = 2e9;  // triangle tests: a few seconds at most
    const Accel brute = make_accel(mesh, AccelKind::Brute);
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const double affordable =
        kBruteBudget / (std::max<double>(double(mesh.triangle_count()), 1) * std::max(rays_per_pixel, 1.0));
    const std::size_t samples =
        std::clamp<std::size_t>(std::size_t(affordable), min_pixels, std::max<std::size_t>(pixels / 37, 1));
    const std::size_t stride = std::max<std::size_t>(pixels / samples, 1);
    std::vector<char> same((pixels + stride - 1) / stride);
    tbb::parallel_for(std::size_t(0), same.size(), [&](std::size_t k) {
        const std::size_t p = k * stride;
        const int i = int(p % std::size_t(width)), j = int(p / std::size_t(width));
        const Vec3 a = radiance(bvh, i, j), b = radiance(brute, i, j);
        const float fa[3] = {a.x, a.y, a.z}, fb[3] = {b.x, b.y, b.z};
        same[k] = same_colour(fa, fb);
    });
    ImageAgreement agreement;
    agreement.pixels = same.size();
    agreement.equal = std::size_t(std::count(same.begin(), same.end(), char(1)));
    return agreement;
}

}  // namespace sombra::bench
