#include "image_compare.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace rt {

std::string compare_result::summary(const compare_tolerance& tol) const {
    if (!same_size) return "the images differ in size";
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%ld of %ld pixels differ by more than %d/255 (%.3f%%, allowed %.3f%%); largest channel difference %d/255",
                  differing_pixels, total_pixels, tol.channel_threshold, 100.0 * differing_fraction(),
                  100.0 * tol.max_differing_fraction, max_channel_difference);
    return buf;
}

compare_result compare_images(const image& actual, const image& expected, const compare_tolerance& tol,
                              image* diff_image) {
    compare_result r;
    r.same_size = actual.width == expected.width && actual.height == expected.height;
    r.total_pixels = long(expected.width) * long(expected.height);
    if (!r.same_size) {
        r.differing_pixels = r.total_pixels;
        return r;
    }
    if (diff_image) *diff_image = image(expected.width, expected.height);
    for (size_t i = 0; i < expected.pixels.size(); ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            int a = linear_to_srgb8(actual.pixels[i][c]);
            int e = linear_to_srgb8(expected.pixels[i][c]);
            worst = std::max(worst, std::abs(a - e));
        }
        r.max_channel_difference = std::max(r.max_channel_difference, worst);
        bool differs = worst > tol.channel_threshold;
        if (differs) ++r.differing_pixels;
        if (diff_image) {
            float level = float(worst) / 255.0f;
            diff_image->pixels[i] = differs ? color(1, 0, 0) : color(level * 4.0f);
        }
    }
    return r;
}

double two_sided_normal_threshold(double p) {
    if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("two_sided_normal_threshold: p must be in (0, 1)");
    // P(|Z| > z) = erfc(z / sqrt 2) falls from 1 to 0 as z grows: bisection.
    double lo = 0.0, hi = 40.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

bool noisy_compare_result::within() const {
    if (!same_size) return false;
    if (tiles_past > 0) return false;
    for (double z : picture_z)
        if (!(std::fabs(z) <= z_max)) return false;
    return true;
}

std::string noisy_compare_result::summary(const noisy_tolerance& tol) const {
    if (!same_size) return "the images differ in size";
    const char names[] = {'R', 'G', 'B'};
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "statistical: %d of %d tiles of %dx%d past |z| <= %.2f (mean difference over its standard error; "
                  "false alarm %.0e per picture); largest tile z %.2f (tile %d,%d, %c); whole picture z R %.2f G %.2f B %.2f",
                  tiles_past, tiles, tol.tile, tol.tile, z_max, tol.false_alarm, worst_tile_z, worst_tile_col,
                  worst_tile_row, names[worst_channel], picture_z[0], picture_z[1], picture_z[2]);
    return buf;
}

namespace {

// Running sums of one set of differences, for its mean's z.
struct difference_sums {
    long n = 0;
    double sum = 0, sum_sq = 0;
    void add(double d) {
        ++n;
        sum += d;
        sum_sq += d * d;
    }
    // mean / (s / sqrt n); 0 when every difference is 0, infinite when they are
    // all equal and not 0 (no noise can explain a constant offset).
    double z() const {
        if (n < 2) return 0.0;
        const double mean = sum / double(n);
        const double var = std::max(0.0, (sum_sq - double(n) * mean * mean) / double(n - 1));
        if (mean == 0.0) return 0.0;
        if (var == 0.0) return mean > 0 ? HUGE_VAL : -HUGE_VAL;
        return mean / std::sqrt(var / double(n));
    }
};

}  // namespace

noisy_compare_result compare_noisy_images(const image& actual, const image& expected, const noisy_tolerance& tol,
                                          image* diff_image) {
    if (tol.tile < 1) throw std::invalid_argument("compare_noisy_images: the tile must be at least 1 pixel");
    noisy_compare_result r;
    r.same_size = actual.width == expected.width && actual.height == expected.height;
    if (!r.same_size) return r;
    const int w = expected.width, h = expected.height, k = tol.tile;
    const int tile_cols = (w + k - 1) / k, tile_rows = (h + k - 1) / k;
    if (diff_image) *diff_image = image(w, h);
    difference_sums picture[3];
    std::vector<char> tile_past(size_t(tile_cols) * size_t(tile_rows), 0);
    std::vector<difference_sums> tiles(size_t(tile_cols) * size_t(tile_rows) * 3);
    for (int row = 0; row < h; ++row)
        for (int col = 0; col < w; ++col) {
            const size_t t = size_t(row / k) * size_t(tile_cols) + size_t(col / k);
            float largest = 0;
            for (int c = 0; c < 3; ++c) {
                const double d = double(linear_to_srgb8(actual.at(col, row)[c])) -
                                 double(linear_to_srgb8(expected.at(col, row)[c]));
                tiles[t * 3 + size_t(c)].add(d);
                picture[c].add(d);
                largest = std::max(largest, float(std::fabs(d)));
            }
            if (diff_image) diff_image->at(col, row) = color(std::min(1.0f, largest * 4.0f / 255.0f));
        }
    int tested = 0;
    for (const difference_sums& s : tiles) tested += s.n >= 2;
    r.tiles = tested / 3;
    r.z_max = two_sided_normal_threshold(tol.false_alarm / double(tested + 3));
    for (int ty = 0; ty < tile_rows; ++ty)
        for (int tx = 0; tx < tile_cols; ++tx) {
            const size_t t = size_t(ty) * size_t(tile_cols) + size_t(tx);
            for (int c = 0; c < 3; ++c) {
                const double z = tiles[t * 3 + size_t(c)].z();
                if (std::fabs(z) > std::fabs(r.worst_tile_z)) {
                    r.worst_tile_z = z;
                    r.worst_tile_col = tx;
                    r.worst_tile_row = ty;
                    r.worst_channel = c;
                }
                if (!(std::fabs(z) <= r.z_max)) tile_past[t] = 1;
            }
            r.tiles_past += tile_past[t];
        }
    for (int c = 0; c < 3; ++c) r.picture_z[c] = picture[c].z();
    if (diff_image)  // outline the tiles past the threshold in red
        for (int row = 0; row < h; ++row)
            for (int col = 0; col < w; ++col) {
                const size_t t = size_t(row / k) * size_t(tile_cols) + size_t(col / k);
                const bool edge = col % k == 0 || row % k == 0 || col % k == k - 1 || row % k == k - 1 ||
                                  col == w - 1 || row == h - 1;
                if (tile_past[t] && edge) diff_image->at(col, row) = color(1, 0, 0);
            }
    return r;
}

}  // namespace rt
