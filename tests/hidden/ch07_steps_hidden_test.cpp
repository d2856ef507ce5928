// Hidden tests for chapter 07, steps 1 to 5 (run by the autograder only).
// Each step on its own, on seeded families of stiff inputs, against a long
// double reference computed from the very inputs the step is given. The
// whole test (step 6) is in ch07_robust_sphere_hidden_test.cpp.
// Failure messages name the idea that went wrong, never the inputs or the
// expected numbers: every check is a plain bool computed beforehand.
#include "07-precision/robust_sphere.hpp"

#include "common/error_metrics.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace rt;

namespace {

using ld = long double;
template <class T>
using W = ch07::wide<T>;

template <class T>
ld value_of(const double_word<W<T>>& x) {
    return ld(x.hi) + ld(x.lo);
}

// A scaled problem whose f, d and radius are W numbers given directly.
template <class T>
ch07::scaled_problem<T> problem(const ld (&f)[3], const ld (&d)[3], ld radius) {
    ch07::scaled_problem<T> p;
    for (int k = 0; k < 3; ++k) {
        p.f[k] = {W<T>(f[k]), 0};
        p.d[k] = W<T>(d[k]);
    }
    p.radius = W<T>(radius);
    return p;
}

// x * y + z * w + ... with every product split (fmal) and the sum compensated:
// about twice long double's digits, enough to judge W = double to a few ULPs.
struct accurate_sum {
    ld sum = 0, err = 0;
    void add(ld x) {
        const ld t = sum + x, bp = t - sum;
        err += (sum - (t - bp)) + (x - bp);
        sum = t;
    }
    void add_product(ld x, ld y) {
        const ld p = x * y;
        add(p);
        err += std::fma(x, y, -p);
    }
    ld value() const { return sum + err; }
};

}  // namespace

// ------------------------------------------------------------------ step 1

TEST_CASE_TEMPLATE("hidden: step1: the quarter discriminant of rays a few ULPs from a far silhouette", T, RT_SCALARS) {
    std::mt19937_64 rng(7101);
    std::uniform_real_distribution<double> log_dist(0.5, 6), log_radius(-3, 3);
    std::uniform_int_distribution<int> steps(1, 64), axis(0, 2), coin(0, 1);
    const ld lengths[] = {1, 0.5, 1.5, 2, 3};
    int wrong_sign = 0, inaccurate = 0;
    for (int i = 0; i < 2000; ++i) {
        // An axis-aligned ray at height y = R moved a few ULPs of T: exactly
        // quarter_disc = a (R - y)(R + y), whatever the distance D.
        const T R = T(std::pow(10.0, log_radius(rng)));
        const T D = T(std::pow(10.0, log_dist(rng)) * double(R));
        const bool inside = coin(rng) == 1;
        T y = R;
        for (int k = steps(rng); k > 0; --k) y = std::nextafter(y, inside ? T(0) : infinity<T>);
        const int ax = axis(rng), up = (ax + 1) % 3;
        const ld s = lengths[i % 5] * (coin(rng) ? 1 : -1);
        ld f[3] = {0, 0, 0}, d[3] = {0, 0, 0};
        f[ax] = ld(D), f[up] = ld(y), d[ax] = s;
        const auto q = ch07::quarter_discriminant(problem<T>(f, d, ld(R)));
        accurate_sum want;
        want.add_product(ld(R) - ld(y), ld(R) + ld(y));  // R - y is exact (Sterbenz)
        const ld exact = want.value() * s * s;
        if (is_negative(q.quarter_disc) != (exact < 0)) ++wrong_sign;
        const ld got = value_of<T>(q.quarter_disc);
        if (!(std::fabs(got - exact) <= std::fabs(exact) * 0x1p-40L)) ++inaccurate;
    }
    const bool sign_ok = wrong_sign == 0;
    CHECK_MESSAGE(sign_ok, "step 1: the quarter discriminant of a ray a few ULPs inside or outside a sphere's "
                           "silhouette had the wrong sign (is it a r^2 - |f x d|^2 with exact products and pairs?)");
    const bool value_ok = inaccurate == 0;
    CHECK_MESSAGE(value_ok, "step 1: the quarter discriminant of a near-tangent ray lost its digits (squares "
                            "subtracted, products not split, or a missing factor a = d.d)");
}

TEST_CASE_TEMPLATE("hidden: step1: a and half_b of random problems", T, RT_SCALARS) {
    std::mt19937_64 rng(7102);
    std::uniform_real_distribution<double> coord(-8, 8);
    int wrong = 0;
    for (int i = 0; i < 2000; ++i) {
        ld f[3], d[3];
        for (int k = 0; k < 3; ++k) f[k] = ld(T(coord(rng))), d[k] = ld(T(coord(rng)));
        const auto q = ch07::quarter_discriminant(problem<T>(f, d, ld(T(1.5))));
        accurate_sum a, h;
        for (int k = 0; k < 3; ++k) a.add_product(d[k], d[k]), h.add_product(f[k], d[k]);
        const ld scale = std::fabs(f[0] * d[0]) + std::fabs(f[1] * d[1]) + std::fabs(f[2] * d[2]);
        if (!(std::fabs(value_of<T>(q.a) - a.value()) <= a.value() * 0x1p-80L) ||
            !(std::fabs(value_of<T>(q.half_b) - h.value()) <= scale * 0x1p-80L))
            ++wrong;
    }
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "step 1: a = d.d or half_b = f.d is not the pair it should be (every product through "
                      "two_prod or the pairs' *, every sum as a pair)");
}

// ------------------------------------------------------------------ step 2

TEST_CASE_TEMPLATE("hidden: step2: stable roots of far-apart roots, either sign of half_b", T, RT_SCALARS) {
    std::mt19937_64 rng(7103);
    std::uniform_real_distribution<double> log_root(-6, 6), log_a(-2, 2);
    std::uniform_int_distribution<int> coin(0, 1);
    int wrong = 0, unordered = 0;
    for (int i = 0; i < 3000; ++i) {
        // Roots of very different sizes: -b -+ sqrt(disc) cancels for the small one.
        const ld r0 = std::pow(10.0L, ld(log_root(rng))) * (coin(rng) ? 1 : -1);
        const ld r1 = std::pow(10.0L, ld(log_root(rng))) * (coin(rng) ? 1 : -1);
        const W<T> a = W<T>(std::pow(10.0L, ld(log_a(rng))));
        const W<T> half_b = W<T>(-ld(a) * (r0 + r1) / 2), c = W<T>(ld(a) * r0 * r1);
        const W<T> disc = W<T>(ld(half_b) * ld(half_b) - ld(a) * ld(c));
        if (!(disc > 0)) continue;
        // The roots of these (rounded) coefficients, in long double.
        const ld q = -(ld(half_b) + std::copysign(std::sqrt(ld(disc)), ld(half_b)));
        ld t0 = ld(c) / q, t1 = q / ld(a);
        if (t1 < t0) std::swap(t0, t1);
        const auto got = ch07::stable_roots<T>(a, half_b, c, disc);
        if (!(got.near <= got.far)) ++unordered;
        if (!(ulp_distance(got.near, W<T>(t0)) <= 4 && ulp_distance(got.far, W<T>(t1)) <= 4)) ++wrong;
    }
    const bool ordered = unordered == 0;
    CHECK_MESSAGE(ordered, "step 2: the roots came back unordered (c / q is the far root when half_b > 0)");
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "step 2: a root is off by more than a few ULPs: q = -(half_b + sign(half_b) sqrt(disc)) "
                      "must add two numbers of the same sign, and the roots are c / q and q / a");
}

// ------------------------------------------------------------------ step 3

TEST_CASE_TEMPLATE("hidden: step3: the constant term of origins near huge spheres", T, RT_SCALARS) {
    std::mt19937_64 rng(7104);
    std::uniform_real_distribution<double> log_r(2, 7), log_h(-4, 0), unit(-1, 1);
    int wrong = 0;
    for (int i = 0; i < 3000; ++i) {
        // f of a point at height h above a sphere of radius R, in a general direction;
        // in double data some low halves too.
        const double R = std::pow(10.0, log_r(rng)), h = std::pow(10.0, log_h(rng)) * (unit(rng) < 0 ? -1 : 1);
        double u[3] = {unit(rng), unit(rng), unit(rng)};
        const double n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        ch07::scaled_problem<T> p;
        p.radius = W<T>(T(R));
        for (int k = 0; k < 3; ++k) {
            p.f[k].hi = W<T>(T(u[k] / n * (R + h)));
            p.f[k].lo = sizeof(T) == sizeof(float) ? 0 : W<T>(T(u[k] * 1e-17 * R));
            p.d[k] = u[k];
        }
        accurate_sum c;
        for (int k = 0; k < 3; ++k) {
            c.add_product(ld(p.f[k].hi), ld(p.f[k].hi));
            c.add_product(2 * ld(p.f[k].hi), ld(p.f[k].lo));
            c.add_product(ld(p.f[k].lo), ld(p.f[k].lo));
        }
        c.add_product(-ld(p.radius), ld(p.radius));
        const ld want = c.value();
        const W<T> got = ch07::constant_term(p);
        if (!(ulp_distance(got, W<T>(want)) <= 4)) ++wrong;
    }
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "step 3: c = f.f - r^2 near a huge sphere is off by more than a few ULPs (split every square "
                      "with two_prod, keep 2 hi lo and lo^2, and add all the pieces with sum_k3)");
}

// ------------------------------------------------------------------ step 4

TEST_CASE_TEMPLATE("hidden: step4: the offset is exact and scaled into range", T, RT_SCALARS) {
    std::mt19937_64 rng(7105);
    // Coordinates of one size (|x| in [0.25, 1) times a power of two): o - C of two of them is exact in long double.
    std::uniform_real_distribution<double> magnitude(0.25, 1), log_scale(-1, 1);
    std::uniform_int_distribution<int> sign(0, 1);
    const auto coord = [&](std::mt19937_64& g) { return magnitude(g) * (sign(g) ? 1 : -1); };
    const int top = std::numeric_limits<T>::max_exponent - 8, bottom = std::numeric_limits<T>::min_exponent + 8;
    std::uniform_int_distribution<int> exponent(bottom, top), small(-30, 30);
    int inexact = 0, out_of_range = 0, inconsistent = 0;
    for (int i = 0; i < 3000; ++i) {
        // Origins near the centre's size: o - C is exact in long double, so it can be checked.
        const int e = i % 3 == 0 ? exponent(rng) : small(rng);
        const T scale = std::ldexp(T(1), e);
        const vec3<T> C(T(coord(rng)) * scale, T(coord(rng)) * scale, T(coord(rng)) * scale);
        const vec3<T> o(T(coord(rng)) * scale, T(coord(rng)) * scale, T(coord(rng)) * scale);
        const T r = T(std::pow(10.0, log_scale(rng))) * scale;
        const int de = i % 5 == 0 ? exponent(rng) : 0;
        const vec3<T> dir(T(coord(rng)) * std::ldexp(T(1), de), T(coord(rng)), T(coord(rng)));
        if (!(r > 0) || !is_finite(o) || !is_finite(C) || !is_finite(dir)) continue;
        const auto p = ch07::scaled_offset(sphere<T>{C, r}, ray<T>{o, dir});
        for (int k = 0; k < 3; ++k) {
            const ld want = std::ldexp(ld(o[k]) - ld(C[k]), p.ef);
            if (value_of<T>(p.f[k]) != want || !(std::fabs(p.f[k].lo) <= std::fabs(p.f[k].hi))) ++inexact;
            if (p.d[k] != std::ldexp(W<T>(dir[k]), p.ed)) ++inconsistent;
        }
        if (p.radius != std::ldexp(W<T>(r), p.ef)) ++inconsistent;
        const W<T> largest = std::max({std::fabs(p.f[0].hi), std::fabs(p.f[1].hi), std::fabs(p.f[2].hi), p.radius});
        const W<T> largest_d = std::max({std::fabs(p.d[0]), std::fabs(p.d[1]), std::fabs(p.d[2])});
        // Comfortable: products of four of them neither overflow nor underflow W.
        const int lim = std::numeric_limits<W<T>>::max_exponent / 4;
        if (!(std::ilogb(largest) < lim && std::ilogb(largest) > -lim && std::ilogb(largest_d) < lim &&
              std::ilogb(largest_d) > -lim))
            ++out_of_range;
    }
    const bool exact = inexact == 0;
    CHECK_MESSAGE(exact, "step 4: f = o - C is not exact: each component must be the pair hi + lo of two_sum");
    const bool consistent = inconsistent == 0;
    CHECK_MESSAGE(consistent, "step 4: the radius must be scaled by the same 2^ef as f, and d by 2^ed");
    const bool in_range = out_of_range == 0;
    CHECK_MESSAGE(in_range, "step 4: tiny or huge inputs were left where their squares under- or overflow (scale "
                            "by powers of two with std::ilogb and std::ldexp)");
}

// ------------------------------------------------------------------ step 5

TEST_CASE_TEMPLATE("hidden: step5: unscaled roots across the whole range", T, RT_SCALARS) {
    std::mt19937_64 rng(7106);
    std::uniform_real_distribution<double> mantissa(1, 2);
    std::uniform_int_distribution<int> exponent(-60, 60);
    const int top = std::numeric_limits<T>::max_exponent, bottom = std::numeric_limits<T>::min_exponent;
    std::uniform_int_distribution<int> shift(bottom - 30, top + 30);
    int wrong = 0;
    for (int i = 0; i < 3000; ++i) {
        const W<T> t = W<T>(mantissa(rng)) * std::ldexp(W<T>(1), exponent(rng)) * (i % 2 ? 1 : -1);
        const int k = shift(rng);
        const ld exact = std::ldexp(ld(t), k);
        const T got = ch07::unscaled_root<T>(t, k);
        const ld M = ld(std::numeric_limits<T>::max());
        bool ok;
        if (std::fabs(exact) > M * (1 + 16 * ld(std::numeric_limits<T>::epsilon())))
            ok = std::isinf(got) && std::signbit(got) == std::signbit(t);
        else if (std::fabs(exact) > M)
            ok = std::fabs(got) == std::numeric_limits<T>::max() || std::isinf(got);
        else
            ok = got == T(exact) || ulp_distance(got, T(exact)) <= 1;  // subnormal results round once
        if (!ok) ++wrong;
    }
    const bool all_ok = wrong == 0;
    CHECK_MESSAGE(all_ok, "step 5: t = t' 2^exponent was not rounded to T once (use std::ldexp in W, then convert; "
                          "beyond T's range infinite with the root's sign)");
}
