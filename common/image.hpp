// image.hpp — a picture in memory, and PNG files on disk.
//
// Pixels are linear RGB floats, row 0 at the top. Writing converts them to
// 8-bit sRGB (the encoding PNG viewers expect); reading converts back to
// linear, so an image survives a write and a read to within 8-bit rounding.
#pragma once

#include "math.hpp"

#include <string>
#include <vector>

namespace rt {

struct image {
    int width = 0;
    int height = 0;
    std::vector<color> pixels;  // row-major, row 0 at the top

    image() = default;
    image(int w, int h, color fill = color(0)) : width(w), height(h), pixels(size_t(w) * size_t(h), fill) {}

    color& at(int col, int row) { return pixels[size_t(row) * size_t(width) + size_t(col)]; }
    const color& at(int col, int row) const { return pixels[size_t(row) * size_t(width) + size_t(col)]; }
};

// 8-bit sRGB encoding of a linear value in [0, 1] (values outside are clamped;
// NaN becomes 0 so a bad pixel is visible as black, never undefined).
unsigned char linear_to_srgb8(float linear);
float srgb8_to_linear(unsigned char encoded);

// Writes img as a PNG. Throws std::runtime_error naming the file on failure.
void write_png(const image& img, const std::string& path);

// The bytes of img as a PNG file (as write_png would write them).
std::vector<unsigned char> encode_png(const image& img);

// Reads a PNG (any channel count; grey is expanded to RGB). Throws
// std::runtime_error naming the file when it cannot be read.
image read_png(const std::string& path);

}  // namespace rt
