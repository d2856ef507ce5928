// Public tests for chapter 07, steps 1 to 5: each step on its own, with the
// lecture's inputs (README, "The exercise"). Run one step's tests with
// ctest -L ch07 -R step1 (step2, ...). Step 6, the whole test, is in
// ch07_robust_sphere_test.cpp.
//
// The inputs are built by hand as scaled_problem values (ef = ed = 0: nothing
// scaled), so a step is tested before the steps that feed it exist. Every
// expected value is exact or was worked out with 60 significant digits.
#include "07-precision/robust_sphere.hpp"

#include "common/error_metrics.hpp"
#include "test_support.hpp"

#include <cmath>
#include <limits>

using namespace rt;
using rt::test::describe;

namespace {

template <class T>
using W = ch07::wide<T>;

// A problem with f given exactly (hi only), d and the radius as given, nothing scaled.
template <class T>
ch07::scaled_problem<T> problem(vec3<T> f, vec3<T> d, T radius) {
    ch07::scaled_problem<T> p;
    for (int k = 0; k < 3; ++k) {
        p.f[k] = {W<T>(f[k]), 0};
        p.d[k] = W<T>(d[k]);
    }
    p.radius = W<T>(radius);
    return p;
}

template <class T>
long double exact(const double_word<W<T>>& x) {
    return static_cast<long double>(x.hi) + static_cast<long double>(x.lo);
}

}  // namespace

// ------------------------------------------------------------------ step 1

TEST_CASE_TEMPLATE("step1: the quarter discriminant of a far sphere keeps its radius", T, RT_SCALARS) {
    // The lecture's trap 1: f = (0.75, 0, 4100), d = (0, 0, -1), radius 1.
    // Exactly: a = 1, half_b = -4100, quarter_disc = r^2 - 0.75^2 = 0.4375.
    const auto q = ch07::quarter_discriminant(problem<T>({T(0.75), 0, 4100}, {0, 0, -1}, T(1)));
    CHECK_MESSAGE(exact<T>(q.a) == 1.0L, "a = d.d = 1 for d = (0, 0, -1); got " << double(exact<T>(q.a)));
    CHECK_MESSAGE(exact<T>(q.half_b) == -4100.0L, "half_b = f.d = -4100; got " << double(exact<T>(q.half_b)));
    CHECK_MESSAGE(exact<T>(q.quarter_disc) == 0.4375L,
                  "the quarter discriminant is r^2 - (distance of the line from the centre)^2 = 1 - 0.75^2 = "
                  "0.4375. half_b^2 - a c gives 0 in float (f.f = 16810000.5625 is stored as 16810000); compute "
                  "a r^2 - |f x d|^2 instead, every product with two_prod. Got "
                      << double(exact<T>(q.quarter_disc)));
}

TEST_CASE_TEMPLATE("step1: the quarter discriminant has the right sign a few ULPs from tangency", T, RT_SCALARS) {
    // A unit sphere 4100 away, rays 2^-20 inside and outside its top: exactly
    // quarter_disc = 1 - y^2 = +-(2^-19 -+ 2^-40).
    const T e = std::ldexp(T(1), -20);
    const auto inside = ch07::quarter_discriminant(problem<T>({0, 1 - e, 4100}, {0, 0, -1}, T(1)));
    const auto outside = ch07::quarter_discriminant(problem<T>({0, 1 + e, 4100}, {0, 0, -1}, T(1)));
    CHECK_MESSAGE(exact<T>(inside.quarter_disc) == 1.0L - (1.0L - e) * (1.0L - e),
                  "2^-20 inside the top the quarter discriminant is exactly 1 - (1 - 2^-20)^2; got "
                      << double(exact<T>(inside.quarter_disc)) << " (is every product split, every sum a pair?)");
    CHECK_MESSAGE(is_negative(outside.quarter_disc),
                  "2^-20 outside the top the quarter discriminant is negative: a miss; got "
                      << double(exact<T>(outside.quarter_disc)));
}

TEST_CASE_TEMPLATE("step1: the quarter discriminant needs a for a direction that is not unit length", T, RT_SCALARS) {
    // d = (0, 0, -2): a = 4, half_b = -2 * 4100, quarter_disc = a (r^2 - 0.75^2) = 1.75.
    const auto q = ch07::quarter_discriminant(problem<T>({T(0.75), 0, 4100}, {0, 0, -2}, T(1)));
    CHECK_MESSAGE(exact<T>(q.a) == 4.0L, "a = d.d = 4; got " << double(exact<T>(q.a)));
    CHECK_MESSAGE(exact<T>(q.quarter_disc) == 1.75L,
                  "quarter_disc = a r^2 - |f x d|^2 = 4 - 2.25 = 1.75 (a r^2, not r^2); got "
                      << double(exact<T>(q.quarter_disc)));
}

// ------------------------------------------------------------------ step 2

TEST_CASE_TEMPLATE("step2: the stable pair gives the near root of the huge ground without cancelling", T, RT_SCALARS) {
    // Trap 2's ray: a = 1.015625, half_b = -125000.125, c = 2000001 and the
    // exact quarter discriminant 15622999999 (all exact in W). Near root
    // 8.000256016385314934, far root 246146.3.
    const auto roots = ch07::stable_roots<T>(W<T>(1.015625), W<T>(-125000.125), W<T>(2000001), W<T>(15622999999.0));
    const double err = ulp_distance(static_cast<W<T>>(roots.near), static_cast<W<T>>(8.000256016385314934L));
    CHECK_MESSAGE(err <= 2, "the near root is 8.000256016385; (-half_b - sqrt) / a cancels (half_b and the root "
                            "agree in four digits): use c / q with q = -(half_b + copysign(sqrt, half_b)). Got "
                                << double(roots.near) << ", " << err << " ULPs away");
    CHECK_MESSAGE((roots.far > 246146 && roots.far < 246147),
                  "the far root is q / a, about 246146.3 (the product of the roots is c / a); got " << double(roots.far));
}

TEST_CASE_TEMPLATE("step2: the stable pair is ordered whatever the sign of half_b", T, RT_SCALARS) {
    // Roots 3 and 5 (a = 1, half_b = -4, c = 15, quarter_disc = 1) and, with the ray reversed, -5 and -3.
    const auto ahead = ch07::stable_roots<T>(1, -4, 15, 1);
    CHECK_MESSAGE((ahead.near == 3 && ahead.far == 5), "roots of t^2 - 8t + 15: 3 and 5, near first; got "
                                                           << double(ahead.near) << " and " << double(ahead.far));
    const auto behind = ch07::stable_roots<T>(1, 4, 15, 1);
    CHECK_MESSAGE((behind.near == -5 && behind.far == -3),
                  "roots of t^2 + 8t + 15: -5 and -3. With half_b > 0, c / q is the far root: compare them. Got "
                      << double(behind.near) << " and " << double(behind.far));
}

TEST_CASE_TEMPLATE("step2: half_b = 0 and a tangent give the double root 0", T, RT_SCALARS) {
    const auto touch = ch07::stable_roots<T>(1, 0, 0, 0);
    CHECK_MESSAGE((touch.near == 0 && touch.far == 0),
                  "q = 0 when half_b = 0 and the discriminant is 0 (the origin touches the sphere): both roots 0, "
                  "not 0 / 0. Got "
                      << double(touch.near) << " and " << double(touch.far));
    const auto centre = ch07::stable_roots<T>(4, 0, -1, 4);  // from the centre of a unit sphere, d of length 2
    CHECK_MESSAGE((centre.near == -0.5 && centre.far == 0.5),
                  "half_b = 0 with a positive discriminant: q = -sqrt(4) = -2, roots c / q = 0.5 and q / a = -0.5. "
                  "Got " << double(centre.near) << " and " << double(centre.far));
}

// ------------------------------------------------------------------ step 3

TEST_CASE_TEMPLATE("step3: the constant term of the huge ground keeps its digits", T, RT_SCALARS) {
    // f = (0, 1000001, 0), radius 1e6: c = 1000001^2 - 1e12 = 2000001 exactly.
    // The plain float c is 2031616, 1.6 % too big.
    const W<T> c = ch07::constant_term(problem<T>({0, 1000001, 0}, {0, -1, 0}, T(1e6)));
    CHECK_MESSAGE(c == W<T>(2000001),
                  "c = f.f - r^2 = 1000001^2 - 1e6^2 = 2000001 exactly; f.f and r^2 agree in their first six "
                  "digits. Split each square with two_prod and add the pieces with sum_k3. Got "
                      << double(c));
}

TEST_CASE_TEMPLATE("step3: the constant term uses the low halves of f", T, RT_SCALARS) {
    // f.y = 1e6 + 2^-10 as the pair (1e6, 2^-10), radius 1e6: c = 2 * 1e6 * 2^-10 + 2^-20.
    auto p = problem<T>({0, T(1e6), 0}, {0, -1, 0}, T(1e6));
    p.f[1].lo = std::ldexp(W<T>(1), -10);
    const W<T> c = ch07::constant_term(p);
    const long double want = 2e6L * std::ldexp(1.0L, -10) + std::ldexp(1.0L, -20);
    CHECK_MESSAGE(std::fabs(static_cast<long double>(c) - want) <= 4 * want * std::numeric_limits<W<T>>::epsilon(),
                  "with f.y = hi + lo = 1e6 + 2^-10, c = 2 hi lo + lo^2 = 1953.125 + 2^-20: the origin is 2^-10 above "
                  "the ground, and only lo says so. Got "
                      << double(c));
    const W<T> on = ch07::constant_term(problem<T>({0, 0, T(-1e6)}, {0, 0, 1}, T(1e6)));
    CHECK_MESSAGE(on == 0, "an origin exactly on the surface has c = 0 exactly; got " << double(on));
}

// ------------------------------------------------------------------ step 4

TEST_CASE_TEMPLATE("step4: the offset f = o - C is exact, as pairs", T, RT_SCALARS) {
    // Origin 0.01 above a sphere of radius 1e6 centred 1e6 below: in float,
    // o.y - C.y = 1000000.01 rounds, but hi + lo is exactly o.y - C.y.
    const sphere<T> s{{0, T(-1e6), 0}, T(1e6)};
    const ray<T> r{{T(3), T(0.01), T(-2)}, {0, -1, 0}};
    const auto p = ch07::scaled_offset(s, r);
    const long double want_y = static_cast<long double>(T(0.01)) + 1e6L;
    CHECK_MESSAGE((p.ef == 0 && p.ed == 0), "nothing here is tiny or huge: ef = ed = 0 (no scaling); got ef = "
                                                << p.ef << ", ed = " << p.ed);
    CHECK_MESSAGE(exact<T>(p.f[1]) == want_y,
                  "f.y = o.y - C.y = 0.01 + 1e6 exactly, as hi + lo from two_sum (in float hi alone is 1000000); "
                  "got hi = " << double(p.f[1].hi) << ", lo = " << double(p.f[1].lo));
    CHECK_MESSAGE((exact<T>(p.f[0]) == 3.0L && exact<T>(p.f[2]) == -2.0L && p.radius == W<T>(1e6) && p.d[1] == -1),
                  "f.x = 3, f.z = -2, the radius and d as given");
}

TEST_CASE_TEMPLATE("step4: tiny and huge inputs are scaled by powers of two", T, RT_SCALARS) {
    // A sphere of radius 2^-100 (float) or 2^-664 (double) and a direction of length 2^-30:
    // f and the radius must come out in [1, 2) times the same power of two, d on its own.
    const int e = sizeof(T) == sizeof(float) ? 100 : 664;
    const T s = std::ldexp(T(1), -e);
    const auto p = ch07::scaled_offset(sphere<T>{{0, 0, -4 * s}, s}, ray<T>{{0, 0, 0}, {0, 0, std::ldexp(T(-1), -30)}});
    const W<T> largest = std::max(std::fabs(p.f[2].hi), p.radius);
    if (sizeof(T) == sizeof(float)) {
        // Float data in double: 2^-100 is comfortable, nothing to scale.
        CHECK_MESSAGE((p.ef == 0 && p.ed == 0),
                      "float data computed in double: 2^-100 and 2^-30 are well inside double's comfortable range, "
                      "so ef = ed = 0; got ef = " << p.ef << ", ed = " << p.ed);
    } else {
        CHECK_MESSAGE((largest >= 1 && largest < 2),
                      "scale f and the radius together so that the largest lies in [1, 2) (std::ilogb, std::ldexp); "
                      "got largest " << double(largest) << " with ef = " << p.ef);
        CHECK_MESSAGE(p.radius == std::ldexp(W<T>(s), p.ef), "the radius is scaled by the same 2^ef as f");
    }
    CHECK_MESSAGE(std::ldexp(p.d[2], -p.ed) == W<T>(std::ldexp(T(-1), -30)),
                  "d times 2^ed, undone by 2^-ed, is the direction again (a power of two loses nothing)");
}

TEST_CASE_TEMPLATE("step4: an origin and a centre near the largest number are quartered", T, RT_SCALARS) {
    // o = -M, C = +M: o - C = -2M overflows T (and double for double data); quartered, it does not.
    const T M = std::numeric_limits<T>::max();
    const auto p = ch07::scaled_offset(sphere<T>{{0, 0, M}, M}, ray<T>{{0, 0, -M}, {0, 0, 1}});
    const bool finite = std::isfinite(p.f[2].hi) && std::isfinite(p.radius);
    CHECK_MESSAGE(finite, "f = o - C must stay finite: quarter o, C and r first when one of them is above a quarter "
                          "of W's largest number, and count the -2 into ef");
    CHECK_MESSAGE(static_cast<long double>(p.f[2].hi) == -2.0L * std::ldexp(static_cast<long double>(M), p.ef),
                  "f.z is -2M times 2^ef; got " << double(p.f[2].hi) << " with ef = " << p.ef);
}

// ------------------------------------------------------------------ step 5

TEST_CASE_TEMPLATE("step5: the unscaled root is t' 2^exponent, rounded once", T, RT_SCALARS) {
    CHECK_MESSAGE(ch07::unscaled_root<T>(W<T>(3), 0) == T(3), "exponent 0: t = t'");
    CHECK_MESSAGE(ch07::unscaled_root<T>(W<T>(1.5), -100) == std::ldexp(T(1.5), -100),
                  "t = t' 2^exponent, exactly (std::ldexp)");
    // In float data, t' = 1 + 2^-40 (a double) rounds to the float 1 once.
    if (sizeof(T) == sizeof(float))
        CHECK_MESSAGE(ch07::unscaled_root<T>(W<T>(1) + std::ldexp(W<T>(1), -40), 0) == T(1),
                      "a double root is rounded to float once, at the end");
}

TEST_CASE_TEMPLATE("step5: beyond the largest number a root is infinite, just above it is the largest", T, RT_SCALARS) {
    const T M = std::numeric_limits<T>::max();
    const W<T> big = std::ldexp(W<T>(1), std::numeric_limits<T>::max_exponent + 2);
    CHECK_MESSAGE(std::isinf(ch07::unscaled_root<T>(big, 0)), "a root 2^(max_exponent + 2) is beyond T: infinite");
    // M / 2 scaled by 2^1 is M; computed one rounding above (the next W above M / 2) it is still M.
    const W<T> half_max_above = std::nextafter(W<T>(M) / 2, infinity<W<T>>);
    CHECK_MESSAGE(ch07::unscaled_root<T>(half_max_above, 1) == M,
                  "a root computed a rounding above T's largest number (ldexp gives infinity for double data) is "
                  "that largest number");
}
