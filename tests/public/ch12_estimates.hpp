// ch12_estimates.hpp — expectations of chapter 12's estimators, measured the
// same way on every run.
//
// A Monte Carlo test must not be a coin flip: its numbers come from a fixed
// low-discrepancy sequence (Roberts' R_d, the additive recurrence
// x_n = frac(1/2 + n * alpha) with alpha_j = phi_d^-(j+1), phi_d the root of
// x^(d+1) = x + 1; "The Unreasonable Effectiveness of Quasirandom
// Sequences", 2018), so every run sees the same paths, and its tolerance
// comes from the estimator's own spread: k standard errors s / sqrt(N), with
// s the sample standard deviation of the N path values. The sequence is
// spread more evenly than random numbers, so the true error is smaller than
// that, never larger in practice; a bias of many standard errors fails.
#pragma once

#include "12-path-tracing/path_tracing.hpp"
#include "12-path-tracing/pixel_random.hpp"

#include <cmath>
#include <functional>
#include <vector>

namespace rt::test::ch12 {

using namespace rt::ch12;

// Point n of the sequence in `dims` dimensions.
inline std::vector<double> quasirandom_point(long n, int dims) {
    double phi = 2.0;  // Newton on x^(d+1) = x + 1
    for (int i = 0; i < 60; ++i) phi -= (std::pow(phi, dims + 1) - phi - 1) / ((dims + 1) * std::pow(phi, dims) - 1);
    std::vector<double> x(static_cast<size_t>(dims));
    double alpha = 1.0;
    for (int j = 0; j < dims; ++j) {
        alpha /= phi;
        const double v = 0.5 + double(n) * alpha;
        x[size_t(j)] = v - std::floor(v);
    }
    return x;
}

// The numbers of path n: five per vertex, for `vertices` vertices, each below
// 1 in T. The first vertex, where most of a pixel's value is decided, takes
// point n of the five-dimensional sequence; the later ones are padded with
// numbers from a fixed-seed stream of path n (a sequence in 5 x 48
// dimensions would not be low-discrepancy in any useful sense: its
// neighbouring coordinates are nearly equal, and the path would be biased).
template <class T>
std::vector<bounce_numbers<T>> quasirandom_path(long n, int vertices) {
    const std::vector<double> first = quasirandom_point(n, 5);
    const auto in_t = [](double v) { return std::min(T(v), std::nextafter(T(1), T(0))); };
    std::vector<bounce_numbers<T>> out = pixel_random(0x5eed, std::uint64_t(n)).path_numbers<T>(vertices);
    out[0] = {in_t(first[0]), in_t(first[1]), in_t(first[2]), in_t(first[3]), in_t(first[4])};
    return out;
}

// Mean and standard error of N values (one channel).
struct estimate {
    double mean = 0, standard_error = 0, largest = 0;
    long count = 0;
    bool finite = true;
};

inline estimate estimate_of(const std::function<double(long)>& value, long count) {
    estimate e;
    double sum = 0, sum_sq = 0;
    for (long n = 0; n < count; ++n) {
        const double v = value(n);
        if (!std::isfinite(v)) e.finite = false;
        sum += v, sum_sq += v * v;
        e.largest = n == 0 ? v : std::max(e.largest, v);
    }
    e.count = count;
    e.mean = sum / double(count);
    const double var = std::max(0.0, (sum_sq - double(count) * e.mean * e.mean) / double(count - 1));
    e.standard_error = std::sqrt(var / double(count));
    return e;
}

// The mean radiance (green channel) along `r` over `count` quasirandom paths.
template <class T>
estimate path_estimate(const path_scene<T>& s, const ray<T>& r, const path_settings& how, long count,
                       int vertices = 48, long first = 1) {
    return estimate_of(
        [&](long n) {
            return double(path_radiance(s, r, {T(0), infinity<T>}, quasirandom_path<T>(first + n, vertices), how).g);
        },
        count);
}

// A white furnace: a closed sphere of radius 10 whose inside reflects half the
// light that reaches it and emits half of `radiance`, so the radiance is
// `radiance` everywhere inside (L = E + a L gives L = E / (1 - a)), and inside
// it two spheres of albedo 1, 0.4 apart, that emit nothing. A correct path
// tracer sees `radiance` in every direction: the spheres vanish. With
// with_light, a large sphere light of that same radiance (albedo 0) hangs
// above them, and next-event estimation samples it: the world is unchanged.
template <class T>
path_scene<T> white_furnace(float radiance, bool with_light) {
    path_scene<T> s;
    s.surfaces = {{color(0.5f), color(0.5f * radiance)}, {color(1.0f), color(0.0f)}, {color(0.0f), color(radiance)}};
    s.geometry.spheres = {{vec3<T>(T(0), T(0), T(0)), T(10), 0},
                          {vec3<T>(T(-1.2), T(0), T(0)), T(1), 1},
                          {vec3<T>(T(1.2), T(0), T(0)), T(1), 1}};
    if (with_light) {
        s.geometry.spheres.push_back({vec3<T>(T(0), T(3), T(0)), T(1.5), 2});
        s.lights = {3};
    }
    return s;
}

// The white furnace with the right sphere made of glass (index 1.5): glass
// absorbs nothing (it reflects the share F and lets the rest through), so it
// vanishes as well, and with_light, the light it lets through to a path must
// be counted (no light sample sees the light through glass).
template <class T>
path_scene<T> glass_furnace(float radiance, bool with_light) {
    path_scene<T> s = white_furnace<T>(radiance, with_light);
    s.surfaces.push_back({color(0.0f), color(0.0f), 1.5f});
    s.geometry.spheres[2].material = int(s.surfaces.size()) - 1;
    return s;
}

// A ray from inside the furnace at the right sphere's side that faces the
// left one (much of what it reflects comes from the other sphere).
template <class T>
ray<T> furnace_view() {
    return {vec3<T>(T(0), T(0.5), T(6)), vec3<T>(T(0.45), T(-0.2), T(-6))};
}

// A ray onto the left sphere's side that faces the right one.
template <class T>
ray<T> furnace_view_of_left() {
    return {vec3<T>(T(0), T(0.3), T(6)), vec3<T>(T(-0.4), T(-0.1), T(-5.5))};
}

// A ray from below onto the right sphere, nearly through its centre and on
// towards the light: through a glass ball, most of its paths reach the light
// straight after leaving the glass.
template <class T>
ray<T> furnace_view_through_right() {
    return {vec3<T>(T(2.6), T(-3.5), T(0.3)), vec3<T>(T(-1.3), T(3.5), T(-0.3))};
}

// A ray onto the top of the right sphere, which sees much of the furnace's light.
template <class T>
ray<T> furnace_view_from_above() {
    return {vec3<T>(T(0.5), T(2), T(5)), vec3<T>(T(0.7), T(-1.1), T(-4.7))};
}

}  // namespace rt::test::ch12
