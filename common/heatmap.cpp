// heatmap.cpp — see heatmap.hpp.
#include "heatmap.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

namespace rt {

long count_map::max() const { return counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end()); }

double count_map::mean() const {
    return counts.empty() ? 0.0 : double(std::accumulate(counts.begin(), counts.end(), 0L)) / double(counts.size());
}

namespace {

constexpr int gap = 4;         // pixels between panels
constexpr int bar_height = 10;  // the colour bar
constexpr int digit_scale = 2;  // each font pixel drawn as 2x2
constexpr int margin = 4;

// The colour of t in [0, 1]: dark blue, purple, orange, pale yellow (an
// approximation of matplotlib's "inferno", which reads in grey too: its
// brightness rises monotonically).
color colour_at(double t) {
    static constexpr std::array<std::array<float, 3>, 5> stops{{
        {0.001f, 0.000f, 0.014f}, {0.258f, 0.039f, 0.406f}, {0.735f, 0.216f, 0.330f},
        {0.978f, 0.557f, 0.035f}, {0.988f, 0.998f, 0.645f}}};
    t = std::clamp(t, 0.0, 1.0) * double(stops.size() - 1);
    const size_t i = std::min(size_t(t), stops.size() - 2);
    const float f = float(t - double(i));
    const auto& a = stops[i];
    const auto& b = stops[i + 1];
    // The stops are sRGB; the image holds linear values.
    auto lin = [](float s) { return srgb8_to_linear((unsigned char)std::lround(s * 255.0f)); };
    return color(lin(a[0] + f * (b[0] - a[0])), lin(a[1] + f * (b[1] - a[1])), lin(a[2] + f * (b[2] - a[2])));
}

// Where a count lies on the logarithmic scale from 0 to top: log(1 + c) / log(1 + top).
double scale_position(long c, long top) {
    return top <= 0 ? 0.0 : std::log1p(double(c)) / std::log1p(double(top));
}

// A 3x5 font for the digits: each row is 3 bits, most significant on the left.
constexpr std::array<std::array<unsigned char, 5>, 10> digit_rows{{
    {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}}};
constexpr int digit_width = (3 + 1) * digit_scale;  // with one column of space

void draw_number(image& img, long value, int left, int top) {
    const std::string text = std::to_string(value);
    for (size_t k = 0; k < text.size(); ++k) {
        const auto& rows = digit_rows[size_t(text[k] - '0')];
        for (int y = 0; y < 5 * digit_scale; ++y)
            for (int x = 0; x < 3 * digit_scale; ++x) {
                const int col = left + int(k) * digit_width + x, row = top + y;
                if ((rows[size_t(y / digit_scale)] >> (2 - x / digit_scale) & 1) && col >= 0 && col < img.width &&
                    row >= 0 && row < img.height)
                    img.at(col, row) = color(1);
            }
    }
}

}  // namespace

image draw_heatmap(const std::vector<count_map>& panels) {
    if (panels.empty()) throw std::invalid_argument("draw_heatmap: no panels");
    const int w = panels[0].width, h = panels[0].height;
    for (const count_map& p : panels)
        if (p.width != w || p.height != h) throw std::invalid_argument("draw_heatmap: panels of different sizes");
    long top = 0;
    for (const count_map& p : panels) top = std::max(top, p.max());

    const int n = int(panels.size());
    const int width = n * w + (n - 1) * gap;
    const int bar_top = h + margin;
    const int labels_top = bar_top + bar_height + 2;
    image img(width, labels_top + 5 * digit_scale + margin, color(0.02f));
    for (int k = 0; k < n; ++k)
        for (int row = 0; row < h; ++row)
            for (int col = 0; col < w; ++col)
                img.at(k * (w + gap) + col, row) = colour_at(scale_position(panels[size_t(k)].counts[size_t(row) * size_t(w) + size_t(col)], top));

    // The bar: position x of the whole width is the scale position x / (width - 1).
    for (int col = 0; col < width; ++col)
        for (int row = bar_top; row < bar_top + bar_height; ++row)
            img.at(col, row) = colour_at(double(col) / double(std::max(1, width - 1)));
    // Marks at 0, at the powers of ten below top, and at top, each numbered
    // where its number does not run into the previous one.
    std::vector<long> marks{0};
    for (long p = 1; p < top; p *= 10) marks.push_back(p);
    if (top > 0) marks.push_back(top);
    int free_from = 0;
    for (long m : marks) {
        const int col = int(std::lround(scale_position(m, top) * double(width - 1)));
        for (int row = bar_top + bar_height - 3; row < bar_top + bar_height + 2; ++row) img.at(col, row) = color(1);
        const int text_width = int(std::to_string(m).size()) * digit_width;
        const int left = std::clamp(col - text_width / 2, 0, width - text_width);
        if (left < free_from) continue;
        draw_number(img, m, left, labels_top);
        free_from = left + text_width + digit_width;
    }
    return img;
}

std::string heatmap_legend(const std::vector<count_map>& panels) {
    std::string out;
    for (const count_map& p : panels) {
        char line[256];
        std::snprintf(line, sizeof line, "  %s: min %ld, mean %.2f, max %ld per pixel\n", p.name.c_str(),
                      p.counts.empty() ? 0L : *std::min_element(p.counts.begin(), p.counts.end()), p.mean(), p.max());
        out += line;
    }
    return out;
}

}  // namespace rt
