// held_out_stiff_test.cpp — stiff cases that contradicted a header's promise:
// chapter 08's slab test with a subnormal direction component, and the
// study's snapped plane at a t near float's largest numbers. Each reference
// is computed in long double from the very float (or double) inputs: a
// difference of two inputs and a quotient of such differences are exact or
// rounded far below the margins the cases are built with (long double has 64
// bits and a range in which every float and double subnormal is normal).
#include "08-acceleration/aabb.hpp"
#include "solutions/07-precision/formulations/plane_formulations.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace rt;

namespace {

// A box [1, 3] x [0, 1] x [-1, 1] (axes rotated by `axis`) and a ray from
// x = 0 along +x that starts k subnormal steps below the box's y = 0 face
// and climbs m subnormal steps per unit t: it enters the y slab at t = k / m
// and stays in it for ~2^149 / m (float) more. The exact answer: a hit
// exactly when k / m <= 3 (entering the x slab at 1, leaving it at 3).
template <class T>
struct subnormal_climb {
    ch08::aabb<T> box;
    ray<T> r;
    long double enter_y;  // the exact slab entry k / m, in long double
};

template <class T>
vec3<T> rotated(T a, T b, T c, int axis) {  // (a, b, c) with b on `axis`
    return axis == 0 ? vec3<T>(b, c, a) : axis == 1 ? vec3<T>(a, b, c) : vec3<T>(c, a, b);
}

template <class T>
subnormal_climb<T> make_climb(std::uint64_t k, std::uint64_t m, bool down, int axis) {
    const T step = std::numeric_limits<T>::denorm_min();
    const T s = down ? T(-1) : T(1);  // down: the mirror image, box y in [-1, 0]
    subnormal_climb<T> c;
    c.box.lo = rotated<T>(T(1), down ? T(-1) : T(0), T(-1), axis);
    c.box.hi = rotated<T>(T(3), down ? T(0) : T(1), T(1), axis);
    c.r.origin = rotated<T>(T(0), -s * T(k) * step, T(0), axis);
    c.r.direction = rotated<T>(T(1), s * T(m) * step, T(0), axis);
    c.enter_y = (0.0L - (long double)(-s * T(k) * step)) / (long double)(s * T(m) * step);
    return c;
}

template <class T>
void check_subnormal_directions() {
    std::mt19937_64 g(8);
    const interval<T> range{T(0), std::numeric_limits<T>::infinity()};
    int hits = 0, false_misses = 0, misses = 0, false_hits = 0;
    for (int i = 0; i < 20000; ++i) {
        const std::uint64_t k = 1 + g() % (1u << 20);
        const double ratio = std::ldexp(double(g() % 1000 + 1), -8);  // k / m from 2^-8 to ~4, or beyond below
        const bool beyond = i % 4 == 3;                                 // a quarter: entry at 3.1 to 100
        const double want = beyond ? 3.1 + double(g() % 970) / 10.0 : std::min(ratio, 2.9);
        const std::uint64_t m = std::max<std::uint64_t>(1, std::uint64_t(double(k) / want));
        const subnormal_climb<T> c = make_climb<T>(k, m, g() % 2 == 0, int(g() % 3));
        const bool exact_hit = c.enter_y <= 3.0L;
        if (std::fabs(c.enter_y - 3.0L) < 0.05L) continue;  // the margin the cases are built with
        const auto got = ch08::intersect_box(c.box, c.r, ch08::reciprocal(c.r.direction), range);
        if (exact_hit) {
            ++hits;
            if (!got) ++false_misses;
            else
                CHECK(std::fabs((long double)*got - std::max(1.0L, c.enter_y)) <= 1e-6L * std::max(1.0L, c.enter_y));
        } else {
            ++misses;
            if (got) ++false_hits;
        }
    }
    INFO(hits << " hits and " << misses << " misses expected");
    CHECK(hits > 10000);
    CHECK(misses > 3000);
    CHECK(false_misses == 0);
    CHECK(false_hits == 0);  // the exit is widened by a few ulps only, not to everything
}

}  // namespace

TEST_CASE("chapter 08's slab test: a subnormal direction component crosses its slab (1/d overflows to +inf)") {
    check_subnormal_directions<float>();
    check_subnormal_directions<double>();
}

// A float ray nearly parallel to a plane of tiny scale: o at 0, the plane
// z = q (q from 2^-29 to 2^-19), the direction's z a few subnormal steps, so
// the plane is met at t from 2^117 to 2^130 (beyond float's largest: skipped); dx up to 4 carries x beyond float's
// largest number for some. A hit reported must have a finite point; a hit
// whose exact point float can hold (below 0.99 of its largest) must be
// reported, at the exact t to float's precision.
TEST_CASE("snapped plane: a reported hit has a finite point (float ray nearly parallel, t near 2^127)") {
    std::mt19937_64 g(7);
    const float big = std::numeric_limits<float>::max();
    const interval<float> range{0.0f, std::numeric_limits<float>::infinity()};
    int reported = 0, representable = 0, beyond = 0;
    for (int i = 0; i < 20000; ++i) {
        const float step = std::numeric_limits<float>::denorm_min();
        const std::uint64_t m = 1 + g() % 8;
        const float q = std::ldexp(1.0f + float(g() % 1000) / 1000.0f, -20 - int(g() % 10));  // the plane z = q, 2^-29 to 2^-19
        const float dx = 1.0f + float(g() % 3000) / 1000.0f;           // 1 to 4
        const float dy = float(int(g() % 2001) - 1000) / 1000.0f;
        const ray<float> r{vec3<float>(0, 0, 0), vec3<float>(dx, dy, float(m) * step)};
        const float scale = std::ldexp(1.0f, -100 + int(g() % 60));    // the normal's length does not matter
        const plane<float> p{vec3<float>(0, 0, q), vec3<float>(0, 0, scale), 0};
        const long double t = (long double)q / ((long double)m * (long double)step);
        if (!(t < (long double)big)) continue;  // t itself beyond float: not this case
        const long double x = t * (long double)dx;
        const auto h = formulations::plane_snapped(r, p, range);
        if (h) {
            ++reported;
            CHECK(is_finite(h->point));
        }
        if (x < 0.99L * (long double)big) {
            ++representable;
            REQUIRE(h);
            CHECK(std::fabs((long double)h->t - t) <= 4e-7L * t);
            CHECK(std::fabs((long double)h->point.x - x) <= 4e-7L * x);
        } else if (x > 1.01L * (long double)big) {
            ++beyond;
            CHECK(!h);  // no float holds the point
        }
    }
    INFO(reported << " reported, " << representable << " representable, " << beyond << " beyond float");
    CHECK(representable > 1000);
    CHECK(beyond > 1000);
}
