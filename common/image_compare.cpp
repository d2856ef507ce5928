#include "image_compare.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

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

}  // namespace rt
