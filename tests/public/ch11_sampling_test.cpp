// Public tests for chapter 11: strata, filters, the sphere light's cone, the thin lens.
//
// Each case is one idea from the lecture. Every exercise takes its random
// numbers as arguments, so these tests choose the numbers: grids of u, the
// corners of the unit square, the number just below 1. Nothing here is
// random, and an answer is checked exactly where the contract is exact.
#include "11-sampling/sampling.hpp"

#include "test_support.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace rt;
using namespace rt::ch11;
using rt::test::close;
using rt::test::describe;

namespace {

template <class T>
const T below_one = std::nextafter(T(1), T(0));

template <class T>
std::string describe2(const vec2<T>& v) {
    return "(" + std::to_string(double(v.x)) + ", " + std::to_string(double(v.y)) + ")";
}

// Which cell of n along one axis x lies in: i with T(i)/T(n) <= x < T(i+1)/T(n), or -1.
template <class T>
int cell_of(T x, int n) {
    for (int i = 0; i < n; ++i)
        if (T(i) / T(n) <= x && x < T(i + 1) / T(n)) return i;
    return -1;
}

// An orthonormal frame around a unit axis, for walking over all directions.
template <class T>
void frame_around(const vec3<T>& w, vec3<T>& t, vec3<T>& b) {
    const vec3<T> helper = std::fabs(w.x) > T(0.5) ? vec3<T>(0, 1, 0) : vec3<T>(1, 0, 0);
    t = normalize(cross(helper, w));
    b = cross(w, t);
}

// The integral of sphere_light_pdf over the sphere of directions, by the
// midpoint rule in (cos theta, phi) around the light's axis. The cone's rim
// cos(theta_max) is a cell boundary (computed in long double), so the
// density is constant on every cell and the rule is exact up to rounding.
template <class T>
long double integrated_density(const sphere<T>& light, const vec3<T>& from, int cells, int angles) {
    using ld = long double;
    const vec3<T> axis = normalize(light.center - from);
    vec3<T> t, b;
    frame_around(axis, t, b);
    const ld d = std::sqrt(ld(dot(light.center - from, light.center - from)));
    const ld cos_max = std::sqrt(1 - (ld(light.radius) / d) * (ld(light.radius) / d));
    const ld pi = 3.14159265358979323846264338327950288L;
    ld total = 0;
    for (int part = 0; part < 2; ++part) {
        const ld lo = part == 0 ? cos_max : -1, hi = part == 0 ? 1 : cos_max;
        const ld dc = (hi - lo) / cells;
        for (int i = 0; i < cells; ++i) {
            const ld c = lo + (i + 0.5L) * dc, s = std::sqrt(1 - c * c);
            for (int j = 0; j < angles; ++j) {
                const ld phi = 2 * pi * (j + 0.5L) / angles;
                const vec3<T> dir = T(s * std::cos(phi)) * t + T(s * std::sin(phi)) * b + T(c) * axis;
                total += ld(sphere_light_pdf(light, from, dir)) * dc * (2 * pi / angles);
            }
        }
    }
    return total;
}

}  // namespace

// --- stratified samples ------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("stratified: each stratum gets exactly one sample", T, RT_SCALARS) {
    const T us[] = {T(0), T(0.25), T(0.5), T(0.999), below_one<T>};
    for (int n = 1; n <= 9; ++n)
        for (T u : us) {
            std::vector<int> count(size_t(n * n), 0);
            for (int k = 0; k < n * n; ++k) {
                const vec2<T> s = stratified_sample(k, n, vec2<T>(u, below_one<T> - u));
                const int i = cell_of(s.x, n), j = cell_of(s.y, n);
                REQUIRE_MESSAGE((i >= 0 && j >= 0), "sample " << k << " of " << n << " x " << n << " is "
                                                              << describe2(s) << ", outside the unit square [0,1)^2");
                CHECK_MESSAGE((i == k % n && j == k / n),
                              "stratum k = " << k << " of " << n << " x " << n << " is column k % n = " << k % n
                                             << ", row k / n = " << k / n << "; its sample " << describe2(s)
                                             << " lies in column " << i << ", row " << j);
                ++count[size_t(j * n + i)];
            }
            for (int c = 0; c < n * n; ++c)
                CHECK_MESSAGE(count[size_t(c)] == 1, "with " << n << " x " << n << " strata, cell " << c << " got "
                                                             << count[size_t(c)] << " samples instead of one");
        }
}

TEST_CASE_TEMPLATE("stratified: u moves the sample inside its stratum, as (i + u) / n", T, RT_SCALARS) {
    const vec2<T> corner = stratified_sample(5, 4, vec2<T>(0, 0));  // column 1, row 1
    CHECK_MESSAGE((corner.x == T(1) / T(4) && corner.y == T(1) / T(4)),
                  "u = (0, 0) is the stratum's lower corner (i / n, j / n) = (0.25, 0.25); got " << describe2(corner));
    const vec2<T> centre = stratified_sample(2, 2, vec2<T>(T(0.5), T(0.5)));  // column 0, row 1
    CHECK_MESSAGE((centre.x == T(0.25) && centre.y == T(0.75)),
                  "u = (0.5, 0.5) is the centre of stratum 2 of 2 x 2, (0.25, 0.75); got " << describe2(centre));
}

TEST_CASE_TEMPLATE("stratified: a u just below 1 stays inside its own stratum", T, RT_SCALARS) {
    // i + u rounds up to i + 1 for u just below 1: the sample would sit on its
    // neighbour's lower edge, and two strata would share a sample.
    for (int n : {3, 7, 10}) {
        const int k = n * n - 1;  // the last column and row
        const vec2<T> s = stratified_sample(k, n, vec2<T>(below_one<T>, below_one<T>));
        CHECK_MESSAGE((s.x < T(1) && s.y < T(1) && s.x >= T(n - 1) / T(n)),
                      "the last stratum of " << n << " x " << n << " with u the largest number below 1 must stay below "
                                                "its upper edge, 1; got " << describe2(s)
                                             << " (keep a value that rounded onto the edge inside the cell)");
    }
}

TEST_CASE_TEMPLATE("stratified: strata and u that do not exist are refused", T, RT_SCALARS) {
    CHECK_THROWS_AS(stratified_sample(4, 2, vec2<T>(0, 0)), std::invalid_argument);   // k = n * n
    CHECK_THROWS_AS(stratified_sample(-1, 2, vec2<T>(0, 0)), std::invalid_argument);
    CHECK_THROWS_AS(stratified_sample(0, 0, vec2<T>(0, 0)), std::invalid_argument);
    CHECK_THROWS_AS(stratified_sample(0, 2, vec2<T>(1, 0)), std::invalid_argument);   // u = 1 is outside [0,1)
    CHECK_THROWS_AS(stratified_sample(0, 2, vec2<T>(0, std::numeric_limits<T>::quiet_NaN())), std::invalid_argument);
}

// --- filters ------------------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("filter: the box counts every sample inside its pixel alike", T, RT_SCALARS) {
    CHECK(filter_weight(filter_kind::box, vec2<T>(0, 0)) == T(1));
    CHECK(filter_weight(filter_kind::box, vec2<T>(T(-0.5), T(0.49))) == T(1));
    CHECK_MESSAGE(filter_weight(filter_kind::box, vec2<T>(T(0.5), T(0))) == T(0),
                  "the box is half-open, [-1/2, 1/2): offset x = +1/2 belongs to the next pixel");
    CHECK(filter_weight(filter_kind::box, vec2<T>(T(0), T(-0.7))) == T(0));
}

TEST_CASE_TEMPLATE("filter: the tent falls linearly to zero one pixel away", T, RT_SCALARS) {
    CHECK(filter_weight(filter_kind::tent, vec2<T>(0, 0)) == T(1));
    const T w = filter_weight(filter_kind::tent, vec2<T>(T(0.5), T(-0.25)));
    CHECK_MESSAGE(close(w, T(0.375)), "the tent is (1 - |x|)(1 - |y|): at (0.5, -0.25) that is 0.5 * 0.75 = 0.375; got " << w);
    CHECK_MESSAGE(filter_weight(filter_kind::tent, vec2<T>(T(1.5), T(0))) == T(0),
                  "outside the tent's support (-1, 1)^2 the weight is 0, never negative");
    CHECK(filter_weight(filter_kind::tent, vec2<T>(std::numeric_limits<T>::quiet_NaN(), T(0))) == T(0));
}

TEST_CASE_TEMPLATE("filter: a pixel of constant colour stays that colour under every filter", T, RT_SCALARS) {
    const color grey(0.3f, 0.55f, 0.8f);
    for (filter_kind f : {filter_kind::box, filter_kind::tent})
        for (int n : {1, 2, 4, 8}) {
            std::vector<pixel_sample<T>> samples;
            for (int k = 0; k < n * n; ++k) {
                const vec2<T> s = stratified_sample(k, n, vec2<T>(T(0.3), T(0.6)));
                samples.push_back({(T(2) * s - T(1)) * filter_radius<T>(f), grey});
            }
            const color c = pixel_estimate(f, samples);
            const float tol = 4.0f * float(n * n + 2) * std::numeric_limits<float>::epsilon();
            CHECK_MESSAGE((std::fabs(c.r - grey.r) <= tol * grey.r && std::fabs(c.g - grey.g) <= tol * grey.g &&
                           std::fabs(c.b - grey.b) <= tol * grey.b),
                          "every sample of the pixel saw (0.3, 0.55, 0.8), so its estimate must be that colour, with the "
                          << (f == filter_kind::box ? "box" : "tent") << " filter and " << n * n
                          << " samples; got (" << c.r << ", " << c.g << ", " << c.b
                          << "): divide the weighted sum by the sum of the weights, not by the number of samples");
        }
    CHECK_MESSAGE(pixel_estimate(filter_kind::box, std::vector<pixel_sample<T>>{}) == color(0.0f),
                  "a pixel without samples is black");
}

// --- the sphere light -----------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("light: points land on the light and inside the cone it subtends", T, RT_SCALARS) {
    const sphere<T> light{{1, 4, -2}, T(0.75), 0};
    const vec3<T> from(0, 0, 0);
    const T d = length(light.center - from);
    const T cos_max = std::sqrt(T(1) - (light.radius / d) * (light.radius / d));
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
            const vec2<T> u(T(i) / T(8), T(j) / T(8) + T(0.01));
            const auto s = sample_sphere_light(light, from, u);
            REQUIRE_MESSAGE(s.has_value(), "a point outside the light always sees it: a sample, not nullopt");
            CHECK_MESSAGE(close(length(s->point - light.center), light.radius, T(1)),
                          "the sample point " << describe(s->point) << " must lie on the light's surface (radius 0.75)");
            CHECK_MESSAGE(rt::test::is_unit(s->direction), "the direction is a unit vector");
            CHECK_MESSAGE(dot(s->direction, normalize(light.center - from)) >= cos_max * (T(1) - T(1e-4)),
                          "the direction " << describe(s->direction) << " leaves the cone the light subtends");
            CHECK_MESSAGE(close(s->point, from + s->distance * s->direction),
                          "point = from + distance * direction");
            CHECK_MESSAGE(dot(s->normal, s->direction) <= T(1e-3),
                          "the point faces `from` (it is the near side of the sphere): normal . direction <= 0");
        }
}

TEST_CASE_TEMPLATE("light: the density integrates to 1 over all directions (quadrature)", T, RT_SCALARS) {
    const vec3<T> from(0, 0, 0);
    for (const sphere<T>& light : {sphere<T>{{0, 3, 0}, T(1), 0}, sphere<T>{{2, -1, 5}, T(0.2), 0},
                                   sphere<T>{{0, 0, -1.5}, T(1.2), 0}}) {
        const long double integral = integrated_density(light, from, 64, 16);
        CHECK_MESSAGE(std::fabs(integral - 1) < 1e-3L,
                      "a density integrates to 1 over the sphere of directions; sphere_light_pdf integrates to "
                          << double(integral) << " for the light at " << describe(light.center) << " (a factor of pi "
                          << "or 2 off? a density per unit area where one per steradian is asked?)");
    }
}

TEST_CASE_TEMPLATE("light: a sample's density is the density of its direction", T, RT_SCALARS) {
    const sphere<T> light{{-1, 2, -3}, T(0.5), 0};
    const vec3<T> from(0, T(0.5), 0);
    const auto s = sample_sphere_light(light, from, vec2<T>(T(0.4), T(0.7)));
    REQUIRE(s.has_value());
    const T pdf = sphere_light_pdf(light, from, s->direction);
    CHECK_MESSAGE(close(s->pdf, pdf), "sample.pdf = " << s->pdf << " but sphere_light_pdf of its direction = " << pdf);
    CHECK_MESSAGE(sphere_light_pdf(light, from, -s->direction) == T(0), "a direction away from the light has density 0");
}

TEST_CASE_TEMPLATE("light: a point on or inside the light has no cone", T, RT_SCALARS) {
    const sphere<T> light{{0, 0, 0}, T(1), 0};
    CHECK_MESSAGE(!sample_sphere_light(light, vec3<T>(T(0.5), 0, 0), vec2<T>(0, 0)).has_value(),
                  "from inside the sphere there is no cone: nullopt");
    CHECK(sphere_light_pdf(light, vec3<T>(T(0.5), 0, 0), vec3<T>(1, 0, 0)) == T(0));
    CHECK_THROWS_AS(sample_sphere_light(sphere<T>{{0, 0, 0}, T(0), 0}, vec3<T>(3, 0, 0), vec2<T>(0, 0)),
                    std::invalid_argument);
    CHECK_THROWS_AS(sample_sphere_light(light, vec3<T>(3, 0, 0), vec2<T>(0, 1)), std::invalid_argument);
}

TEST_CASE_TEMPLATE("light: a small far light keeps its density accurate", T, RT_SCALARS) {
    // 1 - cos(theta_max) computed as 1 - sqrt(1 - s) loses most of its digits
    // when s = (r/d)^2 is small: cos(theta_max) is 1 to many places.
    const T far = sizeof(T) == 4 ? T(300) : T(2e6);
    const sphere<T> light{{0, 0, -far}, T(1), 0};
    const auto s = sample_sphere_light(light, vec3<T>(0, 0, 0), vec2<T>(T(0.5), T(0.5)));
    REQUIRE(s.has_value());
    const long double ratio = 1.0L / (long double)(far) / (long double)(far);
    const long double omc = ratio / (1 + std::sqrt(1 - ratio));
    const long double want = 1 / (2 * 3.14159265358979323846264338327950288L * omc);
    CHECK_MESSAGE(std::fabs((long double)(s->pdf) / want - 1) < 1e-4L,
                  "for a light of radius 1 at distance " << far << " the density is 1 / (2 pi (1 - cos(theta_max))) = "
                      << double(want) << "; got " << s->pdf << " (compute 1 - cos(theta_max) as s / (1 + sqrt(1 - s)))");
}

// --- the thin lens ---------------------------------------------------------------------------------------

namespace {
template <class T>
pinhole_camera<T> test_camera() {
    return pinhole_camera<T>(camera_frame<T>::look_at({T(0.5), 1, 3}, {0, T(0.5), -2}, {0, 1, 0}), T(40), 64, 48);
}
}  // namespace

TEST_CASE_TEMPLATE("lens: with aperture 0 the thin lens is the pinhole camera, bit for bit", T, RT_SCALARS) {
    const pinhole_camera<T> cam = test_camera<T>();
    const thin_lens<T> pinhole{T(0), T(4)};
    for (int row = 0; row < cam.height; row += 7)
        for (int col = 0; col < cam.width; col += 5) {
            const ray<T> want = cam.primary_ray(col, row);
            const ray<T> got =
                thin_lens_ray(cam, pinhole, T(col) + T(0.5), T(row) + T(0.5), vec2<T>(T(0.3), T(0.8)));
            REQUIRE_MESSAGE((got.origin == want.origin && got.direction == want.direction),
                            "pixel (" << col << ", " << row << "): aperture 0 must give camera.primary_ray exactly, "
                                      << describe(want.origin) << " + t " << describe(want.direction) << "; got "
                                      << describe(got.origin) << " + t " << describe(got.direction));
        }
}

TEST_CASE_TEMPLATE("lens: every lens point's ray passes through the point in focus", T, RT_SCALARS) {
    const pinhole_camera<T> cam = test_camera<T>();
    const thin_lens<T> lens{T(0.2), T(5)};
    const ray<T> centre = thin_lens_ray(cam, thin_lens<T>{T(0), T(5)}, T(20.25), T(30.5), vec2<T>(0, 0));
    const vec3<T> in_focus = centre.origin + T(5) * centre.direction;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const ray<T> r = thin_lens_ray(cam, lens, T(20.25), T(30.5), vec2<T>(T(i) / 4 + T(0.1), T(j) / 4));
            CHECK_MESSAGE(close(r.origin + T(5) * r.direction, in_focus),
                          "at t = focus_distance every lens ray reaches the point in focus " << describe(in_focus)
                              << "; got " << describe(r.origin + T(5) * r.direction));
        }
}

TEST_CASE_TEMPLATE("lens: lens points cover the aperture's disc, uniformly by area", T, RT_SCALARS) {
    const pinhole_camera<T> cam = test_camera<T>();
    const thin_lens<T> lens{T(0.3), T(2)};
    T farthest = 0;
    for (int i = 0; i < 16; ++i) {
        const ray<T> r = thin_lens_ray(cam, lens, T(10), T(10), vec2<T>(T(i) / 16 + T(0.06), T(0.37)));
        farthest = std::fmax(farthest, length(r.origin - cam.frame.eye));
        CHECK_MESSAGE(std::fabs(dot(r.origin - cam.frame.eye, cam.frame.w)) < T(1e-4),
                      "the lens lies in the plane through the eye perpendicular to the view direction");
    }
    CHECK_MESSAGE((farthest <= T(0.3) * (1 + T(1e-5)) && farthest > T(0.29)),
                  "lens points spread up to the aperture's radius, 0.3, from the eye; the farthest was " << farthest);
    const ray<T> quarter = thin_lens_ray(cam, lens, T(10), T(10), vec2<T>(T(0.25), T(0.6)));
    CHECK_MESSAGE(close(length(quarter.origin - cam.frame.eye), T(0.15)),
                  "a quarter of the disc's area lies within half its radius: lens_u.x = 0.25 is at radius "
                  "aperture * sqrt(0.25) = 0.15; got " << length(quarter.origin - cam.frame.eye));
}
