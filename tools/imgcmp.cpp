// imgcmp — are two renders the same picture, within tolerance?
//
//   imgcmp ACTUAL.png EXPECTED.png [--threshold 8] [--fraction 0.005] [--diff DIFF.png]
//          [--max-pixels 16777216]
//   imgcmp ACTUAL.png EXPECTED.png --statistical [--tile 16] [--false-alarm 1e-6] [--diff DIFF.png]
//
// --statistical compares noisy (Monte Carlo) pictures: per tile, the mean
// difference against its standard error, estimated from the tile's own
// differences (common/image_compare.hpp, compare_noisy_images), so a correct
// renderer passes on every run and a biased one fails.
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
    bool statistical = false;
    rt::noisy_tolerance noisy;
    app.add_flag("--statistical", statistical,
                 "noisy pictures: per tile, the mean difference against its estimated standard error");
    app.add_option("--tile", noisy.tile, "--statistical: tile side in pixels")
        ->check(CLI::Range(2, 4096))
        ->capture_default_str();
    app.add_option("--false-alarm", noisy.false_alarm,
                   "--statistical: probability that two renders of the same expectation fail, per picture")
        ->check(CLI::Range(1e-300, 0.5))
        ->capture_default_str();
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
        bool matched = false;
        std::string figures;
        if (statistical) {
            const rt::noisy_compare_result r =
                rt::compare_noisy_images(actual, expected, noisy, diff_path.empty() ? nullptr : &diff);
            matched = r.within(), figures = r.summary(noisy);
        } else {
            const rt::compare_result r = rt::compare_images(actual, expected, tol, diff_path.empty() ? nullptr : &diff);
            matched = r.within(tol), figures = r.summary(tol);
        }
        if (!diff_path.empty()) rt::write_png(diff, diff_path);
        std::printf("%s: %s\n", matched ? "match" : "MISMATCH", figures.c_str());
        if (!diff_path.empty()) std::printf("difference image: %s\n", diff_path.c_str());
        return matched ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "imgcmp: %s\n", e.what());
        return 2;
    }
}
