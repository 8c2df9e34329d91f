// The picture's weight map (spec §25): how much each neighbour counts in
// the denoised pixel, as a heat map over the pixels the weights reach.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "explain/explain_denoise.h"
#include "explain/svg_markup.h"

namespace sombra {

namespace {

constexpr float kMapSize = 288.0f;  // the heat map's largest side
constexpr float kMaxCell = 32.0f;   // a small neighbourhood is not blown up beyond this
constexpr float kTitleHeight = 24.0f;
constexpr float kScaleWidth = 240.0f;

struct Rgb {
    double r, g, b;
};
constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kPositive{178, 24, 43};   // red: the neighbour adds its colour
constexpr Rgb kNegative{33, 102, 172};  // blue: it takes its colour away (a regression may)

std::string hex(const Rgb& c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(std::lround(c.r)),
                  static_cast<int>(std::lround(c.g)), static_cast<int>(std::lround(c.b)));
    return buf;
}

// The colour of weight w on a scale that ends at ±largest, white at 0. Its
// strength goes as √|w|: most of a neighbourhood's weights are far below
// the largest, and on a linear scale they would all look white.
std::string colour_of(double w, double largest) {
    const Rgb& end = w < 0.0 ? kNegative : kPositive;
    const double a = largest > 0.0 ? std::sqrt(std::min(std::abs(w) / largest, 1.0)) : 0.0;
    return hex(
        {kWhite.r + a * (end.r - kWhite.r), kWhite.g + a * (end.g - kWhite.g), kWhite.b + a * (end.b - kWhite.b)});
}

std::string weight_text(double w) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", w);
    return buf;
}

// Each pixel's weight, both halves and the mean over the channels, over
// the terms' bounding box (which holds the explained pixel too).
struct WeightGrid {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    std::vector<double> weight;  // row-major
    std::vector<bool> present;   // whether the pixel has a term at all
    double largest = 0.0;        // the largest |weight|: the scale's end
};

WeightGrid grid_of(const DenoisedPixel& d, int x, int y) {
    int x0 = x, x1 = x, y0 = y, y1 = y;
    for (const DenoiseTerm& t : d.terms) {
        x0 = std::min(x0, t.x);
        x1 = std::max(x1, t.x);
        y0 = std::min(y0, t.y);
        y1 = std::max(y1, t.y);
    }
    WeightGrid g{x0, y0, x1 - x0 + 1, y1 - y0 + 1, {}, {}, 0.0};
    const std::size_t cells = static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height);
    g.weight.assign(cells, 0.0);
    g.present.assign(cells, false);
    for (const DenoiseTerm& t : d.terms) {
        const std::size_t i =
            static_cast<std::size_t>(t.y - y0) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(t.x - x0);
        g.weight[i] += (t.weight[0] + t.weight[1] + t.weight[2]) / 3.0;
        g.present[i] = true;
    }
    for (const double w : g.weight) g.largest = std::max(g.largest, std::abs(w));
    return g;
}

}  // namespace

std::string denoise_weight_map(const DenoiseStory& story, int x, int y, float left, float top) {
    const WeightGrid g = grid_of(story.pixel, x, y);
    const float cell =
        std::min({kMapSize / static_cast<float>(g.width), kMapSize / static_cast<float>(g.height), kMaxCell});
    const float map_w = cell * static_cast<float>(g.width), map_h = cell * static_cast<float>(g.height);
    const float map_top = top + kTitleHeight;
    std::ostringstream svg;
    svg << "<g id=\"denoise-weights\">\n";
    svg << "<text x=\"" << svg_number(left) << "\" y=\"" << svg_number(top + 14)
        << "\">Denoising: the weights around pixel (" << x << ", " << y << ")</text>\n";
    svg << "<rect x=\"" << svg_number(left) << "\" y=\"" << svg_number(map_top) << "\" width=\"" << svg_number(map_w)
        << "\" height=\"" << svg_number(map_h) << "\" fill=\"#ffffff\" stroke=\"#cccccc\"/>\n";
    for (int row = 0; row < g.height; ++row)
        for (int col = 0; col < g.width; ++col) {
            const std::size_t i =
                static_cast<std::size_t>(row) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(col);
            if (!g.present[i]) continue;
            // A title per square: a browser shows the pixel and its weight under the pointer.
            svg << "<rect x=\"" << svg_number(left + cell * static_cast<float>(col)) << "\" y=\""
                << svg_number(map_top + cell * static_cast<float>(row)) << "\" width=\"" << svg_number(cell)
                << "\" height=\"" << svg_number(cell) << "\" fill=\"" << colour_of(g.weight[i], g.largest)
                << "\"><title>(" << g.x0 + col << ", " << g.y0 + row << "): w = " << weight_text(g.weight[i])
                << "</title></rect>\n";
        }
    const float px = left + cell * static_cast<float>(x - g.x0), py = map_top + cell * static_cast<float>(y - g.y0);
    svg << "<rect x=\"" << svg_number(px) << "\" y=\"" << svg_number(py) << "\" width=\"" << svg_number(cell)
        << "\" height=\"" << svg_number(cell) << "\" fill=\"none\" stroke=\"#000000\" stroke-width=\"2\"/>\n";

    // The scale: blue (−largest) through white (0) to red (+largest), with
    // ticks where |w| is a quarter of the largest (half-way, on a √ scale).
    const float scale_top = map_top + map_h + 12;
    svg << "<defs><linearGradient id=\"denoise-scale\"><stop offset=\"0\" stop-color=\"" << hex(kNegative)
        << "\"/><stop offset=\"0.5\" stop-color=\"#ffffff\"/><stop offset=\"1\" stop-color=\"" << hex(kPositive)
        << "\"/></linearGradient></defs>\n";
    svg << "<rect x=\"" << svg_number(left) << "\" y=\"" << svg_number(scale_top) << "\" width=\""
        << svg_number(kScaleWidth) << "\" height=\"12\" fill=\"url(#denoise-scale)\" stroke=\"#cccccc\"/>\n";
    for (const float at : {0.25f, 0.75f})
        svg << "<line x1=\"" << svg_number(left + at * kScaleWidth) << "\" y1=\"" << svg_number(scale_top) << "\" x2=\""
            << svg_number(left + at * kScaleWidth) << "\" y2=\"" << svg_number(scale_top + 12)
            << "\" stroke=\"#555555\"/>\n";
    const float label_y = scale_top + 26;
    svg << "<text x=\"" << svg_number(left) << "\" y=\"" << svg_number(label_y) << "\">−" << weight_text(g.largest)
        << "</text>\n";
    svg << "<text x=\"" << svg_number(left + 0.5f * kScaleWidth) << "\" y=\"" << svg_number(label_y)
        << "\" text-anchor=\"middle\">0</text>\n";
    svg << "<text x=\"" << svg_number(left + kScaleWidth) << "\" y=\"" << svg_number(label_y)
        << "\" text-anchor=\"end\">+" << weight_text(g.largest) << "</text>\n";

    // Lines of at most about 50 characters: the panel is kDenoiseMapWidth wide.
    const std::string lines[] = {"A square per pixel: its weight, both halves,",
                                 "the mean over R, G, B. Colour strength √|w|;",
                                 "the ticks mark a quarter of the largest |w|.",
                                 std::string("Columns ")
                                     .append(std::to_string(g.x0))
                                     .append(" to ")
                                     .append(std::to_string(g.x0 + g.width - 1))
                                     .append(", rows ")
                                     .append(std::to_string(g.y0))
                                     .append(" to ")
                                     .append(std::to_string(g.y0 + g.height - 1))
                                     .append(";"),
                                 "the pixel outlined. " + std::to_string(story.pixel.terms.size()) + " terms;",
                                 "the text lists the ten largest."};
    float line_y = label_y + 20;
    for (const std::string& line : lines) {
        svg << "<text x=\"" << svg_number(left) << "\" y=\"" << svg_number(line_y) << "\" fill=\"#555555\">"
            << escape_xml(line) << "</text>\n";
        line_y += 16;
    }
    svg << "</g>\n";
    return svg.str();
}

}  // namespace sombra
