// imgcmp — are two renders the same picture, within tolerance?
//
//   imgcmp ACTUAL.png EXPECTED.png [--threshold 8] [--fraction 0.005] [--diff DIFF.png]
//
// Prints one line with the figures. Exit status: 0 within tolerance, 1 past
// it, 2 when a file cannot be read or the arguments are wrong.
#include "common/image_compare.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

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
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int status = app.exit(e);
        return status == 0 ? 0 : 2;
    }
    try {
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
