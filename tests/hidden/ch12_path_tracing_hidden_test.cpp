// Hidden tests for chapter 12. Feedback names the concept, never the inputs.
// Every estimate uses the fixed sequence of ch12_estimates.hpp, so each
// test gives the same verdict on every run, and a tolerance of a few
// standard errors of the estimator itself.
#include "../public/ch12_estimates.hpp"
#include "12-path-tracing/cornell_box.hpp"

#include "test_support.hpp"

#include <cmath>

using namespace rt;
using namespace rt::ch12;
using rt::test::close;
using namespace rt::test::ch12;

namespace {

template <class T>
std::vector<vec3<T>> hidden_normals() {
    return {normalize(vec3<T>(T(0.6), T(0.1), T(-0.79))), vec3<T>(0, -1, 0), vec3<T>(1, 0, 0),
            normalize(vec3<T>(T(1e-4), T(0), T(-1))), normalize(vec3<T>(T(-0.4), T(0.7), T(0.2)))};
}

// The integral of f(direction) * sin(theta) over the hemisphere of n (midpoint rule).
template <class T, class F>
double hemisphere_integral(const vec3<T>& n, F f) {
    const tangent_frame<T> frame(n);
    const int steps = 40;
    const double pi_d = 3.14159265358979323846, dt = pi_d / 2 / steps, dp = 2 * pi_d / steps;
    double sum = 0;
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
            const double theta = (i + 0.5) * dt, phi = (j + 0.5) * dp;
            const vec3<T> d = frame.to_world(T(std::sin(theta) * std::cos(phi)), T(std::sin(theta) * std::sin(phi)),
                                             T(std::cos(theta)));
            sum += f(d) * std::sin(theta) * dt * dp;
        }
    return sum;
}

// A furnace of radiance 2 along r by bouncing alone (no light samples), with uniform and cosine
// bounces and roulette from the first and the third vertex on: every setting must give 2. The
// paths are the sequence's from `first` on; the messages say what a failure means.
template <class T>
void check_furnace_by_bouncing(const path_scene<T>& furnace, const ray<T>& r, long first, const char* finite_why,
                               const char* why) {
    for (bool cosine : {true, false})
        for (int roulette : {0, 2}) {
            path_settings how;
            how.next_event = false;
            how.cosine_sampling = cosine;
            how.roulette_after = roulette;
            const estimate e = path_estimate(furnace, r, how, 1000, 48, first);
            CHECK_MESSAGE(e.finite, finite_why);
            CHECK_MESSAGE(std::fabs(e.mean - 2.0) <= 5 * e.standard_error + 2e-4, why);
        }
}

// The same furnace, now with a light of radiance 2 in it, along r with light samples (the default
// settings) and uniform and cosine bounces: every setting must still give 2.
template <class T>
void check_furnace_with_light_samples(const path_scene<T>& furnace, const ray<T>& r, long first, const char* why) {
    for (bool cosine : {true, false}) {
        path_settings how;
        how.cosine_sampling = cosine;
        const estimate e = path_estimate(furnace, r, how, 1200, 48, first);
        CHECK_MESSAGE(std::fabs(e.mean - 2.0) <= 5 * e.standard_error + 2e-4, why);
    }
}

}  // namespace

TEST_CASE_TEMPLATE("hidden: the cosine density integrates to one", T, RT_SCALARS) {
    for (const vec3<T>& n : hidden_normals<T>()) {
        const double integral = hemisphere_integral(n, [&](const vec3<T>& d) { return double(cosine_hemisphere_pdf(n, d)); });
        CHECK_MESSAGE(std::fabs(integral - 1.0) < 1e-3, "a density must integrate to 1 over the hemisphere");
    }
}

TEST_CASE_TEMPLATE("hidden: the density below the surface is zero", T, RT_SCALARS) {
    for (const vec3<T>& n : hidden_normals<T>()) {
        CHECK_MESSAGE(cosine_hemisphere_pdf(n, -n) == T(0), "no direction below the surface is ever drawn");
        CHECK_MESSAGE(cosine_hemisphere_pdf(n, vec3<T>(std::nan(""), 0, 0)) == T(0), "a NaN direction has density 0");
    }
}

TEST_CASE_TEMPLATE("hidden: cosine sampling returns the density of the direction it drew", T, RT_SCALARS) {
    for (const vec3<T>& n : hidden_normals<T>())
        for (int i = 0; i < 9; ++i)
            for (int j = 0; j < 9; ++j) {
                const T u1 = (T(i) + T(0.25)) / T(9), u2 = (T(j) + T(0.75)) / T(9);
                const direction_sample<T> s = cosine_hemisphere(n, u1, u2);
                CHECK_MESSAGE(rt::test::is_unit(s.direction), "a sampled direction is unit length");
                CHECK_MESSAGE(close(s.pdf, std::sqrt(T(1) - u1) / pi<T>), "the density is cos(theta) / pi");
                CHECK_MESSAGE(close(dot(n, s.direction), std::sqrt(T(1) - u1)), "Malley's lift: height sqrt(1 - u1)");
            }
}

TEST_CASE_TEMPLATE("hidden: cosine-weighted directions are distributed as cos(theta) / pi", T, RT_SCALARS) {
    // Moments of the drawn directions over a grid of u: E[cos] = 2/3, E[cos^2] = 1/2
    // (uniform directions give 1/2 and 1/3), and no preferred azimuth.
    for (const vec3<T>& n : hidden_normals<T>()) {
        const tangent_frame<T> f(n);
        const int steps = 24;
        double c1 = 0, c2 = 0, along_t = 0;
        for (int i = 0; i < steps; ++i)
            for (int j = 0; j < steps; ++j) {
                const vec3<T> d = cosine_hemisphere(n, (T(i) + T(0.5)) / T(steps), (T(j) + T(0.5)) / T(steps)).direction;
                const double c = double(dot(n, d));
                c1 += c, c2 += c * c, along_t += double(dot(f.t, d));
            }
        const double count = steps * steps;
        CHECK_MESSAGE(std::fabs(c1 / count - 2.0 / 3.0) < 2e-3, "cosine-weighted directions have mean cosine 2/3");
        CHECK_MESSAGE(std::fabs(c2 / count - 0.5) < 2e-3, "cosine-weighted directions have mean squared cosine 1/2");
        CHECK_MESSAGE(std::fabs(along_t / count) < 2e-3, "cosine-weighted directions favour no azimuth");
    }
}

TEST_CASE_TEMPLATE("hidden: the light sample weighs radiance by the BRDF, the cosine and its density", T, RT_SCALARS) {
    const vec3<T> n = normalize(vec3<T>(T(0.2), T(0.3), T(0.9)));
    for (T pdf : {T(0.01), T(1), T(37)})
        for (T c : {T(0.05), T(0.5), T(0.99)}) {
            light_sample<T> l;
            l.direction = tangent_frame<T>(n).to_world(std::sqrt(T(1) - c * c), T(0), c);
            l.pdf = pdf;
            l.radiance = color(3.0f, 0.5f, 9.0f);
            const color albedo(0.25f, 0.8f, 0.1f);
            const color got = light_contribution(albedo, n, l);
            for (int k = 0; k < 3; ++k)
                CHECK_MESSAGE(close(got[k], float(double(albedo[k]) / 3.14159265358979323846 * double(l.radiance[k]) *
                                                  double(c) / double(pdf))),
                              "light sample = albedo / pi * radiance * cos / pdf");
        }
}

TEST_CASE_TEMPLATE("hidden: a light behind the surface or without a sample adds nothing", T, RT_SCALARS) {
    const vec3<T> n(0, 0, 1);
    light_sample<T> l;
    l.radiance = color(5.0f);
    l.direction = normalize(vec3<T>(T(1), T(0), T(-1e-3)));
    l.pdf = T(1);
    CHECK_MESSAGE(light_contribution(color(1.0f), n, l) == color(0.0f), "a light below the surface is black");
    l.direction = n;
    for (T bad : {T(0), T(-1), infinity<T>, T(std::nan(""))}) {
        l.pdf = bad;
        const color c = light_contribution(color(1.0f), n, l);
        CHECK_MESSAGE(c == color(0.0f), "no sample (a pdf that is not a positive finite number) adds nothing");
    }
}

TEST_CASE_TEMPLATE("hidden: roulette leaves the expectation unchanged", T, RT_SCALARS) {
    for (float p : {0.75f, 0.3f, 0.15f}) {
        const int steps = 2000;
        double sum = 0;
        for (int i = 0; i < steps; ++i) sum += double(roulette_weight(color(p / 3, p, p / 2), (T(i) + T(0.5)) / T(steps)));
        CHECK_MESSAGE(std::fabs(sum / steps - 1.0) < 2.0 / (steps * p), "survivors carry 1 / p: the mean weight is 1");
    }
    CHECK_MESSAGE(roulette_weight(color(2.0f, 0.0f, 0.0f), T(0.999)) == T(1), "a throughput of 1 or more always survives");
    CHECK_MESSAGE(roulette_weight(color(-1.0f), T(0)) == T(0), "nothing to carry: the path ends");
    CHECK_MESSAGE(roulette_weight(color(std::nanf("")), T(0)) == T(0), "a NaN throughput ends the path");
}

TEST_CASE_TEMPLATE("hidden: a white furnace returns its radiance", T, RT_SCALARS) {
    const ray<T> r{vec3<T>(T(-0.3), T(-0.6), T(5)), vec3<T>(T(-0.5), T(0.55), T(-5))};
    check_furnace_by_bouncing(white_furnace<T>(2.0f, false), r, 7, "the furnace's paths are finite",
                              "albedo-1 objects in a uniform world vanish: the expectation is the world's radiance");
}

TEST_CASE_TEMPLATE("hidden: next-event estimation counts each light once", T, RT_SCALARS) {
    const ray<T> r{vec3<T>(T(-0.6), T(2.2), T(5)), vec3<T>(T(-0.5), T(-1.3), T(-4.8))};  // the left sphere's top
    check_furnace_with_light_samples(white_furnace<T>(2.0f, true), r, 11,
                                     "a light sampled directly must not be counted again when a bounce hits it");
}

TEST_CASE_TEMPLATE("hidden: a glass ball in a white furnace vanishes", T, RT_SCALARS) {
    const ray<T> r{vec3<T>(T(0.4), T(-0.5), T(5)), vec3<T>(T(0.9), T(0.45), T(-5))};  // onto the glass ball
    check_furnace_by_bouncing(glass_furnace<T>(2.0f, false), r, 13, "paths through glass are finite",
                              "glass absorbs nothing: a glass vertex passes the throughput on unchanged");
}

TEST_CASE_TEMPLATE("hidden: a light reached through glass is counted once", T, RT_SCALARS) {
    const path_scene<T> furnace = glass_furnace<T>(2.0f, true);
    const std::vector<ray<T>> rays = {{vec3<T>(T(2.5), T(-3.3), T(-0.4)), vec3<T>(T(-1.35), T(3.4), T(0.45))},  // through the glass to the light
                                      {vec3<T>(T(1.6), T(2.4), T(5)), vec3<T>(T(-0.3), T(-1.9), T(-5))},  // glass, from above
                                      {vec3<T>(T(-0.2), T(0.1), T(6)), vec3<T>(T(-0.15), T(0.05), T(-5.6))}};  // the matte one
    for (const ray<T>& r : rays)
        check_furnace_with_light_samples(furnace, r, 17,
                                         "after a glass vertex the light a path reaches counts: no light sample saw it");
}

TEST_CASE_TEMPLATE("hidden: energy never grows along a path", T, RT_SCALARS) {
    const path_scene<T> furnace = white_furnace<T>(1.0f, false);
    const ray<T> r{vec3<T>(T(0.1), T(0.2), T(5)), vec3<T>(T(-1), T(0.1), T(-5))};
    // Cosine sampling: each bounce's weight albedo * cos / (pi pdf) is the albedo itself, never above 1.
    // (A uniform bounce weighs 2 albedo cos: one path may grow, only its expectation may not.)
    path_settings how;
    how.next_event = false;
    how.roulette_after = 1 << 30;
    const estimate e = path_estimate(furnace, r, how, 600, 48, 3);
    CHECK_MESSAGE(e.largest <= 1.0 + (sizeof(T) == 4 ? 1e-3 : 1e-9),
                  "a cosine-sampled bounce of albedo <= 1 never increases the throughput");
}

TEST_CASE_TEMPLATE("hidden: next-event estimation and bouncing agree, shadows included", T, RT_SCALARS) {
    const path_scene<T> box = cornell_box<T>();
    // Towards the floor beside the right sphere, towards the back wall, and onto the floor in the
    // right (white) sphere's shadow (the light hidden behind the sphere; the glass ball's shadow
    // is lit by the light it focuses, so it would not show a missing shadow ray).
    const std::vector<ray<T>> rays = {{vec3<T>(T(0), T(1), T(3.3)), vec3<T>(T(0.28), T(-0.55), T(-1))},
                                      {vec3<T>(T(0), T(1), T(3.3)), vec3<T>(T(-0.1), T(0.05), T(-1))},
                                      {vec3<T>(T(0), T(1), T(3.3)), vec3<T>(T(0.6), T(-1), T(-2.98))}};
    for (const ray<T>& r : rays) {
        path_settings nee, bounce;
        bounce.next_event = false;
        const estimate a = path_estimate(box, r, nee, 1000, 24, 5);
        const estimate b = path_estimate(box, r, bounce, 5000, 24, 5);
        const double se = std::sqrt(a.standard_error * a.standard_error + b.standard_error * b.standard_error);
        CHECK_MESSAGE(std::fabs(a.mean - b.mean) <= 5 * se,
                      "light samples and bounces that hit the light estimate the same radiance");
    }
}

TEST_CASE_TEMPLATE("hidden: stiff paths stay finite and never negative", T, RT_SCALARS) {
    const path_scene<T> box = cornell_box<T>();
    const sphere<T> light = box.geometry.spheres[0];
    const std::vector<ray<T>> rays = {
        {vec3<T>(light.center.x + light.radius, light.center.y, T(3)), vec3<T>(T(0), T(0), T(-1))},  // grazing the light
        {vec3<T>(T(0.999999), T(1), T(2)), vec3<T>(T(1e-7), T(0), T(-1))},                            // along a wall
        {vec3<T>(T(0), T(1.9), T(0)), vec3<T>(T(0), T(0.3), T(-1))},  // onto the ceiling, the light behind it
        {vec3<T>(T(0), T(0.01), T(0.9)), vec3<T>(T(0), T(-1), T(0))},  // the floor from just above
    };
    for (const ray<T>& r : rays)
        for (bool next_event : {true, false})
            for (long n = 1; n < 40; ++n) {
                path_settings how;
                how.next_event = next_event;
                const color c = path_radiance(box, r, {T(0), infinity<T>}, quasirandom_path<T>(n, 16), how);
                REQUIRE_MESSAGE((std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b)),
                                "no path returns inf or NaN");
                REQUIRE_MESSAGE((c.r >= 0 && c.g >= 0 && c.b >= 0), "no path returns negative light");
            }
}

TEST_CASE_TEMPLATE("hidden: a surface that would make energy is refused", T, RT_SCALARS) {
    path_scene<T> s = white_furnace<T>(1.0f, false);
    s.surfaces[1].albedo = color(1.2f, 1.0f, 1.0f);
    CHECK_THROWS_AS_MESSAGE(path_radiance(s, furnace_view<T>(), {T(0), infinity<T>}, quasirandom_path<T>(1, 4), path_settings{}),
                            std::invalid_argument, "an albedo above 1 is refused");
    s.surfaces[1].albedo = color(1.0f);
    s.surfaces[0].emission = color(-1.0f);
    CHECK_THROWS_AS_MESSAGE(path_radiance(s, furnace_view<T>(), {T(0), infinity<T>}, quasirandom_path<T>(1, 4), path_settings{}),
                            std::invalid_argument, "a negative emission is refused");
}
