// image_compare.hpp — do two renders show the same picture?
//
// Two correct ray tracers rarely agree to the last bit (a different but
// valid rounding moves a silhouette pixel), so pictures are compared by
// tolerance: a pixel "differs" when any channel differs by more than
// `channel_threshold` 8-bit steps, and the images match when at most
// `max_differing_fraction` of the pixels differ.
#pragma once

#include "image.hpp"

#include <string>

namespace rt {

struct compare_tolerance {
    int channel_threshold = 8;              // in 8-bit sRGB steps (out of 255)
    double max_differing_fraction = 0.005;  // 0.5% of the pixels
};

struct compare_result {
    bool same_size = false;
    long differing_pixels = 0;
    long total_pixels = 0;
    int max_channel_difference = 0;  // in 8-bit steps
    double differing_fraction() const { return total_pixels ? double(differing_pixels) / double(total_pixels) : 1.0; }
    bool within(const compare_tolerance& tol) const {
        return same_size && differing_fraction() <= tol.max_differing_fraction;
    }
    std::string summary(const compare_tolerance& tol) const;
};

// Compares `actual` with `expected`. When diff_image is not null it receives a
// picture of the differences: black where equal, brighter where they differ,
// red where a pixel is past the threshold.
compare_result compare_images(const image& actual, const image& expected, const compare_tolerance& tol,
                              image* diff_image = nullptr);

// --- Noisy pictures: compared by statistics -----------------------------------
//
// A Monte Carlo render (chapter 12) is noisy: two correct renders differ in
// every pixel, by as much as the noise, and a pixel threshold either fails a
// correct renderer or passes a biased one. So the statistical mode asks
// instead whether the two pictures have the same *expected* value, tile by
// tile. Both are drawn by estimators whose pixels are independent (each
// pixel has its own random stream); the reference may be noisy too (drawn
// the same way with other numbers) or converged. Per tile of k x k pixels
// and per channel, with d_i the difference of the two 8-bit codes at pixel i:
//     mean = sum d_i / n,   s^2 = sum (d_i - mean)^2 / (n - 1),   z = mean / (s / sqrt n)
// s / sqrt(n) is the standard error of the mean, estimated from the tile's
// own differences, so the test's scale is the estimator's noise, whatever
// it is: no threshold to tune. Under "same expectation" z is close to a
// standard normal (the central limit theorem over n >= 64 bounded values),
// and |z| > z_max happens with probability false_alarm over the whole picture:
// z_max is chosen for false_alarm / (number of tests) each (Bonferroni),
// the tests being every tile and channel plus the whole picture per channel
// (the whole-picture test is the sensitive one to a small bias everywhere;
// the tiles find a bias in one place). A biased renderer (a missing cosine,
// a light counted twice) moves the mean of many tiles by many standard
// errors and fails. Comparing the 8-bit codes, not linear values, is what
// makes this exact for pictures read from PNG files: clamping and rounding
// are the same functions of the same distribution on both sides. Tiles at
// the right and bottom edges may be smaller; a tile of fewer than 2 pixels
// is skipped. A tile whose differences are all 0 passes; one whose
// differences are all equal and non-zero fails (z is infinite).
struct noisy_tolerance {
    int tile = 16;               // tile side in pixels
    double false_alarm = 1e-6;   // probability that two correct renders fail, for the whole picture
};

struct noisy_compare_result {
    bool same_size = false;
    int tiles = 0;              // tiles tested
    int tiles_past = 0;         // tiles with |z| > z_max in some channel
    double z_max = 0;           // the threshold, from false_alarm and the number of tests
    double worst_tile_z = 0;    // the tile z of largest size (signed: actual brighter is positive)
    int worst_tile_col = 0, worst_tile_row = 0, worst_channel = 0;
    double picture_z[3] = {0, 0, 0};  // the whole picture's z, per channel
    bool within() const;
    std::string summary(const noisy_tolerance& tol) const;
};

// The statistical comparison above. When diff_image is not null it receives
// the absolute difference of each pixel (brighter: larger), with every tile
// past the threshold outlined in red.
noisy_compare_result compare_noisy_images(const image& actual, const image& expected, const noisy_tolerance& tol,
                                          image* diff_image = nullptr);

// The z beyond which a standard normal falls with probability p (both tails):
// P(|Z| > z) = p. For 0 < p < 1.
double two_sided_normal_threshold(double p);

}  // namespace rt
