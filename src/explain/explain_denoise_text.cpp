// The text's "Denoised pixel" section: what the denoiser made of the pixel
// and from which neighbours, as a sum a reader can check by hand.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "explain/describe.h"
#include "explain/explain_denoise.h"

namespace sombra {

namespace {

// `v` with `digits` significant digits ("%.4g"), 0 without a sign.
std::string digits_of(double v, int digits) {
    if (v == 0.0) return "0";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

template <typename T>
std::string triple(const std::array<T, 3>& v, int digits) {
    return std::string("(")
        .append(digits_of(static_cast<double>(v[0]), digits))
        .append(", ")
        .append(digits_of(static_cast<double>(v[1]), digits))
        .append(", ")
        .append(digits_of(static_cast<double>(v[2]), digits))
        .append(")");
}

std::string exact(const std::array<float, 3>& v) { return exact(Vec3{v[0], v[1], v[2]}); }

// How much a term adds to the pixel, |w·c| summed over the channels: what the list is ordered by.
double size_of(const DenoiseTerm& t) {
    double size = 0.0;
    for (std::size_t c = 0; c < 3; ++c) size += std::abs(t.weight[c] * static_cast<double>(t.raw[c]));
    return size;
}

std::string padded(const std::string& text, std::size_t width) {
    return text + std::string(width > text.size() ? width - text.size() : 0, ' ');
}

// The largest terms as a table whose columns line up.
void largest_terms(std::ostringstream& out, const std::vector<DenoiseTerm>& terms) {
    std::vector<const DenoiseTerm*> order;
    for (const DenoiseTerm& t : terms) order.push_back(&t);
    std::stable_sort(order.begin(), order.end(),
                     [](const DenoiseTerm* a, const DenoiseTerm* b) { return size_of(*a) > size_of(*b); });
    order.resize(std::min(order.size(), kDenoiseTextTerms));

    std::vector<std::array<std::string, 5>> rows = {{"pixel", "half", "w", "c", "w·c"}};
    for (const DenoiseTerm* t : order) {
        std::array<double, 3> product{};
        for (std::size_t c = 0; c < 3; ++c) product[c] = t->weight[c] * static_cast<double>(t->raw[c]);
        // append, not "(" + std::to_string(): GCC 12's -Wrestrict misfires on it (its bug 105329).
        rows.push_back(
            {std::string("(").append(std::to_string(t->x)).append(", ").append(std::to_string(t->y)).append(")"),
             t->half == 0 ? "A" : "B", triple(t->weight, 4), triple(t->raw, 4), triple(product, 4)});
    }
    std::array<std::size_t, 5> width{};
    for (const auto& row : rows)
        for (std::size_t k = 0; k < row.size(); ++k) width[k] = std::max(width[k], row[k].size());
    out << "  the " << order.size() << " largest, by |w·c| summed over R, G and B (c: the half's mean colour):\n";
    for (const auto& row : rows) {
        std::string line = "    ";
        for (std::size_t k = 0; k < row.size(); ++k) line += k + 1 < row.size() ? padded(row[k], width[k] + 2) : row[k];
        out << line << "\n";
    }
}

}  // namespace

std::string denoise_text(const DenoiseStory& story, int x, int y) {
    const DenoisedPixel& d = story.pixel;
    std::ostringstream out;
    out << "\nDenoised pixel (" << x << ", " << y << "), as render --denoise makes it with these options\n";
    out << "  raw       " << exact(story.raw) << "  (the mean of all its samples: the image before denoising)\n";
    out << "  denoised  " << exact(d.value) << "  (per channel max(0, Σ w·c) over the terms below)\n";
    std::string clamped;
    const char* const names[3] = {"R", "G", "B"};
    for (std::size_t c = 0; c < 3; ++c)
        if (d.clamped[c]) clamped.append(clamped.empty() ? "" : ", ").append(names[c]);
    out << "  Σ w·c     " << triple(d.unclamped, 7)
        << (clamped.empty() ? "  (none below 0: nothing clamped)" : "  (clamped to 0: " + clamped + ")") << "\n";

    std::array<double, 3> weight_sum{};
    std::size_t pixels = 0;
    int x0 = x, x1 = x, y0 = y, y1 = y;
    for (std::size_t i = 0; i < d.terms.size(); ++i) {
        const DenoiseTerm& t = d.terms[i];
        for (std::size_t c = 0; c < 3; ++c) weight_sum[c] += t.weight[c];
        // The terms come by row, column and half: a pixel's two halves are neighbours.
        if (i == 0 || t.x != d.terms[i - 1].x || t.y != d.terms[i - 1].y) ++pixels;
        x0 = std::min(x0, t.x);
        x1 = std::max(x1, t.x);
        y0 = std::min(y0, t.y);
        y1 = std::max(y1, t.y);
    }
    out << "  " << d.terms.size() << " terms with a nonzero weight w, each half A (even samples) or B (odd) of one of "
        << pixels << " pixels\n";
    out << "    in columns " << x0 << " to " << x1 << " and rows " << y0 << " to " << y1
        << "; per channel the weights add up to " << triple(weight_sum, 6) << "\n";
    largest_terms(out, d.terms);
    return out.str();
}

}  // namespace sombra
