// sampling_study.cpp — how fast the error falls: random, stratified and Halton samples.
//
// A measurement, not an exercise (README, "What stratification buys"). Two
// versions of the chapter's scene, seen through a pinhole (aperture 0, so the
// lens adds no dimension): "edges", lit by a point light, where a pixel's only
// integral is over its area (the checker squares' and spheres' edges); and
// "soft shadow", lit by the sphere light, where a sample also chooses a point
// of the light. Each is drawn with 1, 4, 16, 64 and 256 samples per pixel,
// with each sequence, in float and in double, and compared with a converged
// reference (stratified, 64 x 64 = 4096 samples per pixel, double). Prints
// one CSV line per render (the RMS error over the pixels' linear colours
// against the reference, and the render's time per pixel), then the slope of
// log(error) against log(samples) fitted by least squares per sequence.
//
//   ch11-sampling-study [--width W] [--height H] > tools/study/results/ch11-sampling.csv
#include "picture.hpp"

#include "common/chapter_scenes.hpp"
#include "common/program.hpp"
#include "common/timing.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

using namespace rt;

double rms_difference(const image& a, const image& b) {
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = double(a.pixels[i][c]) - double(b.pixels[i][c]);
            sum += d * d;
        }
    return std::sqrt(sum / double(3 * a.pixels.size()));
}

struct row {
    std::string scene, sequence, precision;
    int spp;
    double ns_per_pixel, rms;
};

template <class T>
image draw(const scene_description& d, int w, int h, ch11::sequence_kind kind, int spp, double& ns_per_pixel) {
    const ch11::sampled_scene<T> scene(d, w, h);
    ch11::picture_settings s;
    s.samples = spp;
    s.sequence = kind;
    s.filter = ch11::filter_kind::box;
    stopwatch sw;
    image img = ch11::render_picture(scene, s);
    ns_per_pixel = sw.nanoseconds() / double(w * h);
    return img;
}

// Least-squares slope of log(rms) against log(spp).
double slope(const std::vector<row>& rows, const std::string& scene, const std::string& seq, const std::string& prec) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const row& r : rows)
        if (r.scene == scene && r.sequence == seq && r.precision == prec) {
            const double x = std::log(double(r.spp)), y = std::log(r.rms);
            n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
        }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int study(int argc, char** argv) {
    int width = 96, height = 72;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--width")) width = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--height")) height = std::atoi(argv[i + 1]);
        else {
            std::fprintf(stderr, "usage: %s [--width W] [--height H]\n", argv[0]);
            return 1;
        }
    }
    const chapter_scene own = chapter_scene_file("ch11");
    scene_description soft = parse_scene(own.text, own.source);
    soft.camera.aperture = 0;
    scene_description edges = soft;
    for (point_light& l : edges.world.lights) l.radius = 0;

    const int spps[] = {1, 4, 16, 64, 256};
    const ch11::sequence_kind kinds[] = {ch11::sequence_kind::random, ch11::sequence_kind::stratified,
                                         ch11::sequence_kind::halton};
    std::vector<row> rows;
    std::printf("scene,sequence,precision,spp,ns_per_pixel,rms_error\n");
    for (const auto& [name, d] : {std::pair<std::string, scene_description>{"edges", edges}, {"soft shadow", soft}}) {
        double ref_ns = 0;
        const image reference = draw<double>(d, width, height, ch11::sequence_kind::stratified, 4096, ref_ns);
        std::fprintf(stderr, "%s: reference (stratified, 4096 spp, double) %.0f ns per pixel\n", name.c_str(), ref_ns);
        for (auto kind : kinds)
            for (int prec = 0; prec < 2; ++prec)
                for (int spp : spps) {
                    row r{name, ch11::sequence_name(kind), prec ? "double" : "float", spp, 0, 0};
                    const image img = prec ? draw<double>(d, width, height, kind, spp, r.ns_per_pixel)
                                           : draw<float>(d, width, height, kind, spp, r.ns_per_pixel);
                    r.rms = rms_difference(img, reference);
                    rows.push_back(r);
                    std::printf("%s,%s,%s,%d,%.1f,%.6g\n", r.scene.c_str(), r.sequence.c_str(), r.precision.c_str(),
                                r.spp, r.ns_per_pixel, r.rms);
                    std::fflush(stdout);
                }
    }
    for (const char* scene : {"edges", "soft shadow"})
        for (auto kind : kinds)
            for (const char* prec : {"float", "double"})
                std::fprintf(stderr, "slope of log(rms) against log(spp): %s, %s, %s: %.2f\n", scene,
                             ch11::sequence_name(kind), prec, slope(rows, scene, ch11::sequence_name(kind), prec));
    return 0;
}

}  // namespace

// A stub reached stops the study politely, as every chapter program does.
int main(int argc, char** argv) { return rt::run_study("ch11-sampling-study", [&] { return study(argc, argv); }); }
