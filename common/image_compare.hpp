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

}  // namespace rt
