// main.cpp — chapter 07's program: the plain sphere test beside the robust one.
//
// The picture has four panels. Left column: chapter 02's intersect_sphere
// (the plain quadratic). Right column: *your* intersect_sphere_robust. Both
// columns run in the precision chosen with --precision (float by default,
// because float is where the lecture's failures show).
//
//   top row     the far spheres: three unit spheres seen by an orthographic
//               camera from 100, 4100 and 20000 units away. An orthographic
//               camera draws them the same size, so each should be the same
//               round ball; the plain float test flattens or loses the far ones.
//   bottom row  the huge ground: a sphere of radius 1e6 as the ground, the
//               camera 1 unit above it, two small balls standing on it. The
//               plain float test frays the checkerboard where its near root
//               cancels; the robust test draws it clean.
//
// With --error the program also reports, for each column, how many pixels
// changed from hit to miss (or back) against the reference solution's answers
// for the same rays (reference_hits.bin, numbers made from the solutions),
// and the median and largest error in t in ULPs of the chosen precision. For
// a picture size the file does not hold, the reference is your own robust
// test in long double (a mistake made in both precisions then cancels out).
#include "picture_scenes.hpp"
#include "robust_sphere.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "02-sphere/sphere.hpp"

#include "common/camera.hpp"
#include "common/error_metrics.hpp"
#include "common/program.hpp"
#include "common/render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace rt;

using namespace rt::ch07_picture;

// --------------------------------------------------- the two sphere tests

enum class formula { plain, robust };

template <class T>
std::optional<hit_record<T>> intersect(formula fm, const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    return fm == formula::plain ? ch02::intersect_sphere(s, r, range) : ch07::intersect_sphere_robust(s, r, range);
}

// ---------------------------------------------------------------- shading

color sky(float up) {
    const float s = std::clamp(0.5f * (up + 1.0f), 0.0f, 1.0f);
    return (1.0f - s) * color(1.0f, 1.0f, 1.0f) + s * color(0.5f, 0.7f, 1.0f);
}

template <class T>
color shade(which_scene sc, const ray<T>& r, const std::optional<hit_record<T>>& hit, int material) {
    if (!hit) return sc == which_scene::far_spheres ? color(0.08f, 0.08f, 0.1f) : sky(float(normalize(r.direction).y));
    const color n = convert<float>(hit->normal);
    if (sc == which_scene::huge_ground && material == 0) {
        // A checkerboard of 0.25-unit squares: a wrong t moves the hit point
        // along the ray, and the squares' edges show it as fraying.
        const double x = double(hit->point.x), z = double(hit->point.z);
        if (!(std::fabs(x) < 1e9 && std::fabs(z) < 1e9)) return color(1.0f, 0.0f, 1.0f);  // no sane point: magenta
        const bool dark = (long(std::floor(x * 4)) + long(std::floor(z * 4))) % 2 != 0;
        const float light = 0.35f + 0.65f * std::max(0.0f, n.y);
        return (dark ? color(0.25f, 0.25f, 0.3f) : color(0.9f, 0.85f, 0.7f)) * light;
    }
    return n * 0.5f + 0.5f;  // the outward normal as a colour
}

// Panel layout: 2 x 2, left column plain, right column robust; top row far
// spheres, bottom row huge ground.
struct panel {
    which_scene scene;
    formula fm;
    int col, row, width, height;  // pixel inside the panel, and the panel's size
};

panel locate(int col, int row, int width, int height) {
    const int half_w = width / 2, half_h = height / 2;
    panel p;
    p.fm = col < half_w ? formula::plain : formula::robust;
    p.scene = row < half_h ? which_scene::far_spheres : which_scene::huge_ground;
    p.col = col < half_w ? col : col - half_w;
    p.row = row < half_h ? row : row - half_h;
    p.width = col < half_w ? half_w : width - half_w;
    p.height = row < half_h ? half_h : height - half_h;
    return p;
}

template <class T>
image render_panels(const program_options& opt) {
    const std::vector<sphere<T>> far = spheres_of<T>(which_scene::far_spheres);
    const std::vector<sphere<T>> ground = spheres_of<T>(which_scene::huge_ground);
    return render(opt.width, opt.height, [&](int col, int row) {
        const panel p = locate(col, row, opt.width, opt.height);
        if (p.col == 0 && col > 0) return color(0.0f);  // a thin line between the columns
        if (p.row == 0 && row > 0) return color(0.0f);  // and between the rows
        const std::vector<sphere<T>>& spheres = p.scene == which_scene::far_spheres ? far : ground;
        const ray<T> r = panel_ray<T>(p.scene, opt.view, p.col, p.row, p.width, p.height);
        ch03::object_intersector<T> one = [&](int i, const ray<T>& rr, const interval<T>& range) {
            return intersect(p.fm, spheres[size_t(i)], rr, range);
        };
        auto hit = ch03::closest_hit<T>(int(spheres.size()), one, r, visible_range<T>(p.scene));
        return shade(p.scene, r, hit, hit ? spheres[size_t(hit->object)].material : -1);
    });
}

// ------------------------------------------------------------ error report

// Per (pixel, sphere) pair: does the ray hit that sphere, and where? The
// reference answers are for the very same inputs (the T ray and the T
// sphere), so what remains is the error of the formula in T, not of the
// scene description.
struct error_tally {
    long wrong_hit_or_miss = 0;  // pixels where some sphere's hit/miss differs from the reference
    std::vector<double> ulps;    // |t - t_ref| in ULPs of T, for each pair both call a hit

    // The median says how good a typical hit is; the maximum is what makes holes.
    double quantile(double q) {
        if (ulps.empty()) return 0;
        const size_t k = std::min(ulps.size() - 1, size_t(q * double(ulps.size())));
        std::nth_element(ulps.begin(), ulps.begin() + long(k), ulps.end());
        return ulps[k];
    }
};

template <class T>
ray<long double> widen(const ray<T>& r) {
    return {convert<long double>(r.origin), convert<long double>(r.direction)};
}

template <class T>
sphere<long double> widen(const sphere<T>& s) {
    return {convert<long double>(s.center), static_cast<long double>(s.radius), s.material};
}

// The reference t of sphere i for the ray through (col, row): from the
// file when it holds this picture size, else your robust test in long double.
template <class T>
std::optional<T> reference_t(const std::optional<reference_answers<T>>& file, const sphere<T>& s, int i,
                             const ray<T>& r, const interval<T>& range, int col, int row) {
    if (file) return file->at(col, row, i);
    const interval<long double> wide_range{static_cast<long double>(range.min), static_cast<long double>(range.max)};
    auto hit = ch07::intersect_sphere_robust(widen(s), widen(r), wide_range);
    return hit ? std::optional<T>(static_cast<T>(hit->t)) : std::nullopt;
}

template <class T>
error_tally measure(which_scene sc, const view_turn& view, formula fm, int width, int height,
                    const std::optional<reference_answers<T>>& file) {
    const std::vector<sphere<T>> spheres = spheres_of<T>(sc);
    const interval<T> range = visible_range<T>(sc);
    error_tally tally;
    for (int row = 0; row < height; ++row) {
        for (int col = 0; col < width; ++col) {
            const ray<T> r = panel_ray<T>(sc, view, col, row, width, height);
            bool pixel_wrong = false;
            for (int i = 0; i < int(spheres.size()); ++i) {
                auto got = intersect(fm, spheres[size_t(i)], r, range);
                auto want = reference_t(file, spheres[size_t(i)], i, r, range, col, row);
                if (got.has_value() != want.has_value()) {
                    pixel_wrong = true;
                } else if (got) {
                    tally.ulps.push_back(ulp_distance(got->t, *want));
                }
            }
            if (pixel_wrong) ++tally.wrong_hit_or_miss;
        }
    }
    return tally;
}

template <class T>
std::string error_report(const program_options& opt) {
    const int w = opt.width / 2, h = opt.height / 2;  // one panel's size
    if (w == 0 || h == 0) return "the image is too small for 2 x 2 panels: nothing to measure";
    std::string out, why;
    const char* scene_names[] = {"far spheres", "huge ground"};
    const char* formula_names[] = {"plain (ch02)", "robust (ch07)"};
    for (which_scene sc : both_scenes) {
        // The file holds the rays of the chapter's own view only.
        const auto file = opt.view.is_own_view() ? read_reference<T>(RT_CH07_REFERENCE_HITS, sc, w, h, why)
                                                 : std::nullopt;
        if (!opt.view.is_own_view()) why = "the reference file holds the chapter's own view, not --view's";
        if (out.empty())
            out = (file ? std::string("against the reference solution's answers (reference_hits.bin), per ")
                        : "against your robust test in long double (" + why + "), per ") +
                  std::to_string(w) + "x" + std::to_string(h) + " panel:";
        out += std::string("\n  ") + scene_names[int(sc)] + ":";
        for (formula fm : {formula::plain, formula::robust}) {
            error_tally e = measure<T>(sc, opt.view, fm, w, h, file);
            char line[200];
            std::snprintf(line, sizeof line, "  %s: %ld px hit/miss wrong, t error median %.3g / max %.3g ULP;",
                          formula_names[int(fm)], e.wrong_hit_or_miss, e.quantile(0.5), e.quantile(1.0));
            out += line;
        }
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    rt::chapter_program program;
    program.id = "ch07";
    program.title = "precision";
    program.default_width = 640;
    program.default_height = 480;
    // Float by default (the other chapters default to double): the lecture's
    // failures are float failures. Try --precision double as well.
    program.default_precision = rt::precision::single;
    program.render = rt::by_precision(render_panels<float>, render_panels<double>);
    program.error_report = [](const rt::program_options& opt) {
        return opt.prec == rt::precision::single ? error_report<float>(opt) : error_report<double>(opt);
    };
    return rt::run_chapter_program(argc, argv, program);
}
