#include "image.hpp"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace rt {

unsigned char linear_to_srgb8(float linear) {
    if (!(linear > 0.0f)) return 0;  // also catches NaN
    if (linear >= 1.0f) return 255;
    float encoded = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return static_cast<unsigned char>(std::lround(encoded * 255.0f));
}

float srgb8_to_linear(unsigned char value) {
    float encoded = float(value) / 255.0f;
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

namespace {
// The 8-bit sRGB bytes a PNG of img holds, row by row.
std::vector<unsigned char> srgb8_bytes(const image& img) {
    std::vector<unsigned char> bytes(img.pixels.size() * 3);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) bytes[3 * i + size_t(c)] = linear_to_srgb8(img.pixels[i][c]);
    return bytes;
}

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
}
}  // namespace

void write_png(const image& img, const std::string& path) {
    if (img.width <= 0 || img.height <= 0) throw std::runtime_error(path + ": cannot write an empty image");
    const std::vector<unsigned char> bytes = srgb8_bytes(img);
    if (!stbi_write_png(path.c_str(), img.width, img.height, 3, bytes.data(), img.width * 3))
        throw std::runtime_error(path + ": could not write the PNG file (does its folder exist?)");
}

std::vector<unsigned char> encode_png(const image& img) {
    if (img.width <= 0 || img.height <= 0) throw std::runtime_error("cannot encode an empty image as PNG");
    const std::vector<unsigned char> bytes = srgb8_bytes(img);
    std::vector<unsigned char> png;
    if (!stbi_write_png_to_func(append_bytes, &png, img.width, img.height, 3, bytes.data(), img.width * 3))
        throw std::runtime_error("could not encode the image as PNG");
    return png;
}

image read_png(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> data(stbi_load(path.c_str(), &w, &h, &channels, 3),
                                                         stbi_image_free);
    if (!data) {
        const char* why = stbi_failure_reason();
        throw std::runtime_error(path + ": could not read the image (" + (why ? why : "unknown reason") + ")");
    }
    image img(w, h);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) img.pixels[i][c] = srgb8_to_linear(data.get()[3 * i + size_t(c)]);
    return img;
}

}  // namespace rt
