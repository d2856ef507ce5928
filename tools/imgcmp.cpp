// imgcmp — are two renders the same picture, within tolerance?
//
//   imgcmp ACTUAL.png EXPECTED.png [--threshold 8] [--fraction 0.005] [--diff DIFF.png]
//          [--max-pixels 16777216]
//
// Prints one line with the figures. Exit status: 0 within tolerance, 1 past
// it, 2 when a file cannot be read or the arguments are wrong.
//
// ACTUAL is often a student's file, read by the grader: its header is read
// first, and a picture claiming more pixels than the reference (a different
// size never matches) or than --max-pixels is never decoded, so a 20-byte
// PNG header claiming 8192x8192 pixels costs nothing.
#include "common/image_compare.hpp"

#include <CLI/CLI.hpp>
#include <stb/stb_image.h>

#include <cstdio>
#include <exception>
#include <stdexcept>

namespace {
struct png_size {
    long width = 0, height = 0;
};

// The size a PNG file claims, from its header only (nothing is decoded).
png_size claimed_size(const std::string& path, long max_pixels) {
    int w = 0, h = 0, channels = 0;
    if (!stbi_info(path.c_str(), &w, &h, &channels)) {
        const char* why = stbi_failure_reason();
        throw std::runtime_error(path + ": could not read the image header (" + (why ? why : "unknown reason") + ")");
    }
    if (w <= 0 || h <= 0 || long(w) * long(h) > max_pixels)
        throw std::runtime_error(path + ": claims " + std::to_string(w) + "x" + std::to_string(h) +
                                 " pixels, more than the " + std::to_string(max_pixels) + " imgcmp decodes");
    return {w, h};
}
}  // namespace

int main(int argc, char** argv) {
    std::string actual_path, expected_path, diff_path;
    rt::compare_tolerance tol;
    CLI::App app{"imgcmp: compares two PNG images by tolerance"};
    app.add_option("actual", actual_path, "the image to check")->required();
    app.add_option("expected", expected_path, "the reference image")->required();
    app.add_option("--threshold", tol.channel_threshold, "a pixel differs when a channel differs by more than this (0-255)")
        ->check(CLI::Range(0, 255))
        ->capture_default_str();
    app.add_option("--fraction", tol.max_differing_fraction, "largest fraction of differing pixels allowed")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--diff", diff_path, "write a difference image here");
    long max_pixels = 4096L * 4096L;
    app.add_option("--max-pixels", max_pixels, "refuse (exit status 2) a picture claiming more pixels than this")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int status = app.exit(e);
        return status == 0 ? 0 : 2;
    }
    try {
        const png_size want = claimed_size(expected_path, max_pixels);
        const png_size got = claimed_size(actual_path, 1L << 62);   // any size: a different one is never decoded
        if (got.width != want.width || got.height != want.height) {
            std::printf("MISMATCH: the images differ in size (%ldx%ld, expected %ldx%ld)\n", got.width, got.height,
                        want.width, want.height);
            return 1;
        }
        rt::image actual = rt::read_png(actual_path);
        rt::image expected = rt::read_png(expected_path);
        rt::image diff;
        rt::compare_result r = rt::compare_images(actual, expected, tol, diff_path.empty() ? nullptr : &diff);
        if (!diff_path.empty() && r.same_size) rt::write_png(diff, diff_path);
        std::printf("%s: %s\n", r.within(tol) ? "match" : "MISMATCH", r.summary(tol).c_str());
        if (!diff_path.empty() && r.same_size) std::printf("difference image: %s\n", diff_path.c_str());
        return r.within(tol) ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "imgcmp: %s\n", e.what());
        return 2;
    }
}
