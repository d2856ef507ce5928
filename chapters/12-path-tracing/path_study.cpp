// path_study.cpp — how fast the error falls against time: the lecture's four estimators.
//
// A measurement, not an exercise (README, "What each estimator buys"). The
// chapter's Cornell box is drawn by *your* path_radiance (picture.hpp) with
// each estimator: uniform hemisphere bounces, cosine-weighted bounces,
// next-event estimation with uniform bounces, and next-event estimation with
// cosine bounces ("both"), each at 1, 4, 16, ... paths per pixel, in float and
// in double. Each picture is compared with a converged reference: next-event
// estimation with cosine bounces in double, --reference-spp paths per pixel,
// drawn as two halves with different seeds, so that half their difference
// says how much noise the reference itself still has (its RMS, printed: the
// floor under every error below). Prints one CSV line per picture: the RMS
// error over the pixels' linear colours (as measured, and with the
// reference's noise taken out: the two are independent, so their variances
// add), the render's processor time per path
// (both threads' CPU seconds: little changed by other work on the machine)
// and its wall-clock time per path on every core (render_threads(): what the
// other engineers' load slows down). Then, per estimator and precision, the
// least-squares slope of log(error) against log(paths) (-1/2 for an unbiased
// estimator whose variance stays finite) and its cost of one unit of
// variance, error^2 x time, compared with that of "both" (both from the
// error with the reference's noise taken out).
//
//   ch12-path-study [--width W] [--height H] [--max-spp N] [--reference-spp N] > out/ch12-path-study.csv
#include "cornell_box.hpp"
#include "picture.hpp"

#include "common/program.hpp"
#include "common/timing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

using namespace rt;

struct estimator {
    const char* name;
    bool next_event, cosine;
};
const estimator estimators[] = {{"uniform", false, false}, {"cosine", false, true}, {"nee", true, false},
                                {"both", true, true}};

double rms_difference(const image& a, const image& b, double scale = 1) {
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = (double(a.pixels[i][c]) - double(b.pixels[i][c])) * scale;
            sum += d * d;
        }
    return std::sqrt(sum / double(3 * a.pixels.size()));
}

struct timed_image {
    image img;
    double cpu_seconds = 0, wall_seconds = 0;
};

template <class T>
timed_image draw(const scene_description& d, int width, int height, const ch12::picture_settings& how) {
    const ch12::path_scene<T> box = ch12::path_scene_of<T>(d);
    const pinhole_camera<T> camera = ch12::path_camera<T>(d, width, height);
    const double cpu0 = process_cpu_seconds();
    stopwatch wall;
    timed_image out;
    out.img = ch12::render_picture(box, camera, how);
    out.wall_seconds = wall.seconds();
    out.cpu_seconds = process_cpu_seconds() - cpu0;
    return out;
}

struct row {
    std::string estimator, precision;
    int spp;
    double cpu_ns_per_path, wall_ns_per_path, rms;
    double rms_of_estimator;  // rms with the reference's own noise taken out: sqrt(rms^2 - noise^2)
};

// Least-squares slope of log(rms) against log(spp) for one estimator and precision.
double slope(const std::vector<row>& rows, const std::string& name, const std::string& prec) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const row& r : rows)
        if (r.estimator == name && r.precision == prec) {
            const double x = std::log(double(r.spp)), y = std::log(r.rms_of_estimator);
            n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
        }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// error^2 x processor time per pixel at the largest spp: the variance one
// nanosecond per pixel buys down to (smaller is better; equal for all spp
// when the slope is -1/2).
double variance_times_time(const std::vector<row>& rows, const std::string& name, const std::string& prec) {
    const row* last = nullptr;
    for (const row& r : rows)
        if (r.estimator == name && r.precision == prec && (!last || r.spp > last->spp)) last = &r;
    return last ? last->rms_of_estimator * last->rms_of_estimator * last->cpu_ns_per_path * last->spp : 0;
}

int usage(const char* program) {
    std::fprintf(stderr, "usage: %s [--width W] [--height H] [--max-spp N] [--reference-spp N]\n", program);
    return 1;
}

int study(int argc, char** argv) {
    int width = 48, height = 48, max_spp = 64, reference_spp = 1024;
    for (int i = 1; i < argc; i += 2) {
        if (i + 1 >= argc) return usage(argv[0]);
        const int value = std::atoi(argv[i + 1]);
        if (!std::strcmp(argv[i], "--width")) width = value;
        else if (!std::strcmp(argv[i], "--height")) height = value;
        else if (!std::strcmp(argv[i], "--max-spp")) max_spp = value;
        else if (!std::strcmp(argv[i], "--reference-spp")) reference_spp = value;
        else return usage(argv[0]);
    }
    if (width < 1 || height < 1 || max_spp < 1 || reference_spp < 2) return usage(argv[0]);
    const scene_description box = ch12::cornell_box_file();
    const double paths_per_spp = double(width) * double(height);

    // The reference: "both" in double, two halves with their own seeds.
    ch12::picture_settings ref;
    ref.paths = reference_spp / 2;
    ref.seed = 1000001;
    const timed_image half_a = draw<double>(box, width, height, ref);
    ref.seed = 1000002;
    const timed_image half_b = draw<double>(box, width, height, ref);
    image reference = half_a.img;
    for (size_t i = 0; i < reference.pixels.size(); ++i)
        reference.pixels[i] = (half_a.img.pixels[i] + half_b.img.pixels[i]) * 0.5f;
    // Each half's noise is sqrt(2) times the whole's; their difference has twice a half's variance.
    const double reference_noise = rms_difference(half_a.img, half_b.img, 0.5);
    const double reference_paths = 2.0 * ref.paths * paths_per_spp;
    const double reference_cpu = half_a.cpu_seconds + half_b.cpu_seconds;
    const double reference_wall = half_a.wall_seconds + half_b.wall_seconds;
    std::fprintf(stderr,
                 "reference: next-event estimation with cosine bounces, double, %d paths per pixel at %dx%d, "
                 "%.1f s of processor time, %.1f s wall on %d threads (%.0f ns of processor time per path, "
                 "%.0f ns wall per path on all of them); its own RMS noise about %.3g\n",
                 2 * ref.paths, width, height, reference_cpu, reference_wall, render_threads(),
                 reference_cpu * 1e9 / reference_paths, reference_wall * 1e9 / reference_paths, reference_noise);

    std::vector<int> spps;
    for (int spp = 1; spp <= max_spp; spp *= 4) spps.push_back(spp);
    std::vector<row> rows;
    std::printf("estimator,precision,spp,cpu_ns_per_path,wall_ns_per_path,rms_error,rms_error_less_reference_noise\n");
    for (const estimator& e : estimators)
        for (int prec = 0; prec < 2; ++prec)
            for (int spp : spps) {
                ch12::picture_settings how;
                how.paths = spp;
                how.seed = 1;
                how.estimator.next_event = e.next_event;
                how.estimator.cosine_sampling = e.cosine;
                const timed_image t = prec ? draw<double>(box, width, height, how) : draw<float>(box, width, height, how);
                const double paths = paths_per_spp * spp;
                const double rms = rms_difference(t.img, reference);
                // The reference's noise is independent of the picture's: their variances add.
                const double of_estimator = std::sqrt(std::max(0.0, rms * rms - reference_noise * reference_noise));
                row r{e.name, prec ? "double" : "float", spp, t.cpu_seconds * 1e9 / paths, t.wall_seconds * 1e9 / paths,
                      rms, of_estimator};
                rows.push_back(r);
                std::printf("%s,%s,%d,%.1f,%.1f,%.6g,%.6g\n", r.estimator.c_str(), r.precision.c_str(), r.spp,
                            r.cpu_ns_per_path, r.wall_ns_per_path, r.rms, r.rms_of_estimator);
                std::fflush(stdout);
            }
    const double both_double = variance_times_time(rows, "both", "double");
    for (const estimator& e : estimators)
        for (const char* prec : {"float", "double"})
            std::fprintf(stderr,
                         "%s, %s: slope of log(rms) against log(spp) %.2f; rms^2 x processor ns per pixel at %d spp "
                         "%.3g (%.2f x that of both, double)\n",
                         e.name, prec, slope(rows, e.name, prec), spps.back(), variance_times_time(rows, e.name, prec),
                         variance_times_time(rows, e.name, prec) / both_double);
    return 0;
}

}  // namespace

// A stub reached stops the study politely, as every chapter program does.
int main(int argc, char** argv) { return rt::run_study("ch12-path-study", [&] { return study(argc, argv); }); }
