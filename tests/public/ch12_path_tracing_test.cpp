// Public tests for chapter 12: hemisphere sampling, the light sample,
// Russian roulette, the path loop, and the white furnace.
//
// Each case is one idea from the lecture. Estimates of an expectation use a
// fixed low-discrepancy sequence (ch12_estimates.hpp), so a test gives the
// same answer on every run, and a tolerance of a few standard errors of the
// estimator itself: never a pixel threshold.
#include "ch12_estimates.hpp"
#include "12-path-tracing/cornell_box.hpp"

#include "test_support.hpp"

#include <cmath>
#include <string>

using namespace rt;
using namespace rt::ch12;
using rt::test::close;
using rt::test::describe;
using namespace rt::test::ch12;

namespace {

// A few normals, axis-aligned and slanted (the frame's hard case is n.z = -1).
template <class T>
std::vector<vec3<T>> some_normals() {
    return {vec3<T>(0, 0, 1), vec3<T>(0, 0, -1), vec3<T>(0, 1, 0), normalize(vec3<T>(T(0.3), T(-0.5), T(0.8))),
            normalize(vec3<T>(T(-1e-3), T(1e-3), T(-1)))};
}

std::string describe_estimate(const estimate& e) {
    return "mean " + std::to_string(e.mean) + " +- " + std::to_string(e.standard_error) + " (one standard error, " +
           std::to_string(e.count) + " paths)";
}

}  // namespace

TEST_CASE_TEMPLATE("cosine_hemisphere_pdf is cos(theta) / pi above the surface and 0 below", T, RT_SCALARS) {
    const vec3<T> n(0, 0, 1);
    const vec3<T> sixty = normalize(vec3<T>(std::sqrt(T(3)), T(0), T(1)));  // cos = 1/2
    INFO("the density of cosine-weighted sampling is max(0, cos(theta)) / pi (README, 'Cosine-weighted sampling')");
    CHECK(close(cosine_hemisphere_pdf(n, n), T(1) / pi<T>));
    CHECK(close(cosine_hemisphere_pdf(n, sixty), T(0.5) / pi<T>));
    CHECK(cosine_hemisphere_pdf(n, vec3<T>(0, 0, -1)) == T(0));
    CHECK(cosine_hemisphere_pdf(n, vec3<T>(1, 0, 0)) == T(0));
}

TEST_CASE_TEMPLATE("the cosine density integrates to 1 over the hemisphere", T, RT_SCALARS) {
    // The midpoint rule in (theta, phi), solid angle sin(theta) dtheta dphi: a
    // density that is off by a factor (pi, 2) integrates to that factor.
    for (const vec3<T>& n : some_normals<T>()) {
        const tangent_frame<T> f(n);
        const int steps = 48;
        double integral = 0;
        for (int i = 0; i < steps; ++i)
            for (int j = 0; j < steps; ++j) {
                const double theta = (i + 0.5) / steps * 3.14159265358979323846 / 2;
                const double phi = (j + 0.5) / steps * 2 * 3.14159265358979323846;
                const vec3<T> d = f.to_world(T(std::sin(theta) * std::cos(phi)), T(std::sin(theta) * std::sin(phi)),
                                             T(std::cos(theta)));
                integral += double(cosine_hemisphere_pdf(n, d)) * std::sin(theta) * (3.14159265358979323846 / 2 / steps) *
                            (2 * 3.14159265358979323846 / steps);
            }
        INFO("normal " << describe(n) << ": the density integrates to " << integral
             << "; every density must integrate to 1 (the integral of cos(theta) over the hemisphere is pi)");
        CHECK(std::fabs(integral - 1.0) < 1e-3);  // the midpoint rule's own error is below 1e-4
    }
}

TEST_CASE_TEMPLATE("cosine_hemisphere lifts the disc onto the hemisphere and returns the matching density", T, RT_SCALARS) {
    for (const vec3<T>& n : some_normals<T>()) {
        const direction_sample<T> top = cosine_hemisphere(n, T(0), T(0.3));
        INFO("u1 = 0 is the disc's centre, lifted straight up: the normal itself; got " << describe(top.direction));
        CHECK(close(top.direction, n));
        for (int i = 0; i < 16; ++i)
            for (int j = 0; j < 16; ++j) {
                const T u1 = (T(i) + T(0.5)) / T(16), u2 = (T(j) + T(0.5)) / T(16);
                const direction_sample<T> s = cosine_hemisphere(n, u1, u2);
                INFO("normal " << describe(n) << ", u = (" << u1 << ", " << u2 << "): direction " << describe(s.direction)
                               << ", pdf " << s.pdf);
                CHECK(rt::test::is_unit(s.direction));
                CHECK(close(dot(n, s.direction), std::sqrt(T(1) - u1)));  // the height is sqrt(1 - u1)
                CHECK(close(s.pdf, cosine_hemisphere_pdf(n, s.direction)));
            }
    }
}

TEST_CASE_TEMPLATE("cosine-weighted directions have the mean cosine 2/3 (uniform ones: 1/2)", T, RT_SCALARS) {
    // E[cos] under the density cos / pi is the integral of cos^2 / pi: 2/3.
    const vec3<T> n = normalize(vec3<T>(T(0.2), T(0.9), T(-0.3)));
    const int steps = 32;
    double sum = 0;
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j)
            sum += double(dot(n, cosine_hemisphere(n, (T(i) + T(0.5)) / T(steps), (T(j) + T(0.5)) / T(steps)).direction));
    const double mean = sum / (steps * steps);
    INFO("mean cos(theta) over a grid of u: " << mean << "; cosine-weighted sampling must give 2/3 (1/2 means the"
         " directions are uniform, whatever density is returned with them)");
    CHECK(std::fabs(mean - 2.0 / 3.0) < 1e-3);
}

TEST_CASE_TEMPLATE("light_contribution is BRDF x radiance x cosine / density", T, RT_SCALARS) {
    const vec3<T> n(0, 1, 0);
    light_sample<T> l;
    l.direction = normalize(vec3<T>(T(1), T(1), T(0)));  // cos = 1/sqrt(2)
    l.pdf = T(2);
    l.radiance = color(4.0f, 2.0f, 1.0f);
    const color albedo(0.5f, 0.5f, 1.0f);
    const color got = light_contribution(albedo, n, l);
    const double c = 1 / std::sqrt(2.0) / 3.14159265358979323846 / 2;
    INFO("albedo / pi * radiance * cos(theta) / pdf; got (" << got.r << ", " << got.g << ", " << got.b << ")");
    CHECK(close(got.r, float(0.5 * 4 * c)));
    CHECK(close(got.g, float(0.5 * 2 * c)));
    CHECK(close(got.b, float(1.0 * 1 * c)));
    l.direction = vec3<T>(0, -1, 0);
    INFO("a light below the surface adds nothing");
    CHECK(light_contribution(albedo, n, l) == color(0.0f));
    l.direction = vec3<T>(0, 1, 0);
    l.pdf = T(0);
    INFO("no sample (pdf 0) adds nothing, never inf");
    CHECK(light_contribution(albedo, n, l) == color(0.0f));
}

TEST_CASE_TEMPLATE("roulette keeps the expected weight at 1", T, RT_SCALARS) {
    INFO("a throughput of 1 or more always survives with weight 1; black always ends");
    CHECK(roulette_weight(color(1.0f, 0.2f, 0.0f), T(0.99)) == T(1));
    CHECK(roulette_weight(color(0.0f), T(0)) == T(0));
    for (float p : {0.9f, 0.5f, 0.125f}) {
        const int steps = 2000;
        double sum = 0;
        for (int i = 0; i < steps; ++i) sum += double(roulette_weight(color(p, p / 2, 0.0f), (T(i) + T(0.5)) / T(steps)));
        INFO("throughput " << p << ": the mean weight over u is " << sum / steps
             << "; a survivor must carry 1/p, so the mean stays 1 (roulette must not lose energy)");
        CHECK(std::fabs(sum / steps - 1.0) < 2.0 / (steps * p));
    }
}

TEST_CASE_TEMPLATE("white furnace: albedo-1 spheres in a uniform world vanish", T, RT_SCALARS) {
    const path_scene<T> furnace = white_furnace<T>(1.0f, false);
    for (bool cosine : {true, false}) {
        path_settings how;
        how.next_event = false;
        how.cosine_sampling = cosine;
        const estimate e = path_estimate(furnace, furnace_view<T>(), how, 1500);
        INFO((cosine ? "cosine" : "uniform") << " sampling: " << describe_estimate(e)
             << "; the furnace's radiance is 1 everywhere, and a path tracer must return it in expectation");
        CHECK(e.finite);
        CHECK(std::fabs(e.mean - 1.0) <= 5 * e.standard_error + 1e-4);
    }
}

TEST_CASE_TEMPLATE("white furnace with a light: next-event estimation counts the light once", T, RT_SCALARS) {
    const path_scene<T> furnace = white_furnace<T>(1.0f, true);
    path_settings how;
    how.next_event = true;
    const estimate e = path_estimate(furnace, furnace_view_from_above<T>(), how, 1500);
    INFO(describe_estimate(e) << "; the light's radiance equals the world's, so the answer stays 1: more means the "
         "light is counted twice (by its sample and again when a bounce hits it)");
    CHECK(std::fabs(e.mean - 1.0) <= 5 * e.standard_error + 1e-4);
}

TEST_CASE_TEMPLATE("white furnace: a glass ball vanishes too, for it absorbs nothing", T, RT_SCALARS) {
    const path_scene<T> furnace = glass_furnace<T>(1.0f, false);
    for (const ray<T>& r : {furnace_view<T>(), furnace_view_of_left<T>()}) {
        path_settings how;
        how.next_event = false;
        const estimate e = path_estimate(furnace, r, how, 1500);
        INFO(describe_estimate(e) << "; glass reflects the share F and lets 1 - F through, so its throughput goes on "
             "unchanged (glass_bounce): a glass vertex must not end the path nor weigh it by an albedo");
        CHECK(e.finite);
        CHECK(std::fabs(e.mean - 1.0) <= 5 * e.standard_error + 1e-4);
    }
}

TEST_CASE_TEMPLATE("next-event estimation counts the light a path reaches through glass", T, RT_SCALARS) {
    const path_scene<T> furnace = glass_furnace<T>(1.0f, true);
    path_settings how;
    how.next_event = true;
    for (const ray<T>& r : {furnace_view_through_right<T>(), furnace_view_from_above<T>(), furnace_view_of_left<T>()}) {
        const estimate e = path_estimate(furnace, r, how, 1500);
        INFO(describe_estimate(e) << "; the answer stays 1. Less means a light reached through glass was dropped: the "
             "light sample of a matte vertex stops at the glass (a shadow), so only the path through the glass brings "
             "that light, and after a glass vertex the light's emission counts");
        CHECK(std::fabs(e.mean - 1.0) <= 5 * e.standard_error + 1e-4);
    }
}

TEST_CASE_TEMPLATE("energy never grows along a path", T, RT_SCALARS) {
    // Without roulette and light samples, a furnace path's value is a sum of
    // emission (1/2) times throughputs that shrink by the wall's albedo (1/2)
    // at each wall hit: never more than 1/2 + 1/4 + ... = 1.
    const path_scene<T> furnace = white_furnace<T>(1.0f, false);
    path_settings how;
    how.next_event = false;
    how.roulette_after = 1 << 30;
    const estimate e = path_estimate(furnace, furnace_view<T>(), how, 600);
    INFO("the largest single path value is " << e.largest << "; above 1 means a bounce's weight albedo * cos / (pi pdf) "
         "grew the throughput");
    CHECK(e.largest <= 1.0 + (sizeof(T) == 4 ? 1e-3 : 1e-9));  // rounding, over up to 48 bounces
}

TEST_CASE_TEMPLATE("next-event estimation and plain bouncing agree in expectation", T, RT_SCALARS) {
    const path_scene<T> box = cornell_box<T>();
    const ray<T> to_floor{vec3<T>(T(0), T(1), T(3.3)), vec3<T>(T(0.1), T(-0.6), T(-1))};
    path_settings nee, bounce;
    bounce.next_event = false;
    const estimate a = path_estimate(box, to_floor, nee, 1200);
    const estimate b = path_estimate(box, to_floor, bounce, 6000, 24);
    const double se = std::sqrt(a.standard_error * a.standard_error + b.standard_error * b.standard_error);
    INFO("with light samples " << describe_estimate(a) << ", without " << describe_estimate(b)
         << ": two estimators of the same integral");
    CHECK(a.standard_error < b.standard_error);  // the point of sampling the light
    CHECK(std::fabs(a.mean - b.mean) <= 5 * se);
}

TEST_CASE_TEMPLATE("stiff cases stay finite: grazing rays, lights behind the surface", T, RT_SCALARS) {
    const path_scene<T> box = cornell_box<T>();
    const sphere<T> ball = box.geometry.spheres[1];
    const std::vector<ray<T>> rays = {
        {vec3<T>(ball.center.x - ball.radius, ball.center.y, T(3)), vec3<T>(T(0), T(0), T(-1))},  // tangent
        {vec3<T>(T(0), T(1e-6), T(2)), vec3<T>(T(0), T(-1e-7), T(-1))},                         // along the floor
        {vec3<T>(T(0), T(1.99), T(0)), vec3<T>(T(0), T(1), T(0))},                                // ceiling, light behind
    };
    for (const ray<T>& r : rays)
        for (long n = 1; n < 60; ++n) {
            const color c = path_radiance(box, r, {T(0), infinity<T>}, quasirandom_path<T>(n, 16), path_settings{});
            INFO("ray from " << describe(r.origin) << ": radiance (" << c.r << ", " << c.g << ", " << c.b << ")");
            REQUIRE((std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b)));
            REQUIRE((c.r >= 0 && c.g >= 0 && c.b >= 0));
        }
    light_sample<T> l;
    l.direction = vec3<T>(0, 1, 0);
    l.pdf = infinity<T>;
    l.radiance = color(1.0f);
    INFO("an infinite density (a point light seen as an area) adds nothing, never NaN");
    CHECK(light_contribution(color(1.0f), vec3<T>(0, 1, 0), l) == color(0.0f));
}
