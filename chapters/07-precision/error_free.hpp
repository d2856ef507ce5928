// error_free.hpp — exact sums and products, and numbers made of two floats.
//
// Chapter 07's toolbox (README, "Exact pieces"), given to you: the exercise
// steps build on it, and so do the reference solution, the formulation study
// (solutions/07-precision/formulations) and the renderer. One vocabulary for
// error-free arithmetic in the whole course: double_word, two_sum, two_prod.
//
// The rounding error of one addition or multiplication is itself a
// floating-point number, and it can be computed exactly:
//   * two_sum(a, b)  gives s = fl(a + b) and e with  a + b = s + e  exactly
//     (Knuth's six-operation trick, valid for any a, b without overflow);
//   * two_prod(a, b) gives p = fl(a * b) and e with  a * b = p + e  exactly,
//     because a fused multiply-add fma(a, b, -p) rounds only once (or, on
//     a target without FMA instructions, by Dekker's splitting product).
// Carrying the pair (value, error) through a computation gives about twice
// the precision of T (a "double-word" number: float-float or double-double).
// That is what lets a float routine subtract two nearly equal quantities
// (c = f.f - r^2 on the ground sphere) and keep the digits that survive.
//
// Never compile this with -ffast-math: the compiler would simplify
// (a - (s - b)) to zero and every error term would vanish.
//
// The helpers are declared inline: they are a handful of operations each,
// and a call per operation would cost more than the arithmetic.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace rt {

// A number hi + lo with |lo| <= half an ulp of hi.
template <class T>
struct double_word {
    T hi = 0;
    T lo = 0;
    T value() const { return hi + lo; }
};

template <class T>
inline double_word<T> two_sum(T a, T b) {
    T s = a + b;
    T bb = s - a;
    T e = (a - (s - bb)) + (b - bb);
    return {s, e};
}

// The error term of two_sum alone, for a sum s = fl(a + b) already at hand.
template <class T>
inline T two_sum_error(T a, T b, T s) {
    T bb = s - a;
    return (a - (s - bb)) + (b - bb);
}

// The error of s = fl(a - b): a - b = s + two_diff_error(a, b, s) exactly.
template <class T>
inline T two_diff_error(T a, T b, T s) {
    T bb = s - a;
    return (a - (s - bb)) - (b + bb);
}

// Only when |a| >= |b| (or a == 0): three operations instead of six.
template <class T>
inline double_word<T> fast_two_sum(T a, T b) {
    T s = a + b;
    return {s, b - (s - a)};
}

// Veltkamp's split: a = hi + lo, each half with at most half the
// significand bits, so products of halves are exact (Dekker's product).
// Valid while |a| stays well below the overflow threshold / 2^(bits/2).
// The factor is 2^ceil(p/2) + 1 for a p-bit significand: 2^12 + 1 for
// float, 2^27 + 1 for double, 2^32 + 1 for x86's 64-bit long double.
template <class T>
inline double_word<T> split(T a) {
    constexpr int half = (std::numeric_limits<T>::digits + 1) / 2;
    constexpr T factor = T(1ull << half) + T(1);
    T c = factor * a;
    T hi = c - (c - a);
    return {hi, a - hi};
}

// With a hardware FMA (compiled with -mfma or -march=native on x86-64,
// always on ARM64) the error of a product is one instruction. Without it,
// std::fma is a library call of several nanoseconds, and Dekker's product
// (17 plain operations, exact as well) is much faster, so it is used.
#if defined(FP_FAST_FMA) && defined(FP_FAST_FMAF)
inline constexpr bool fma_in_hardware = true;
#else
inline constexpr bool fma_in_hardware = false;
#endif

template <class T>
inline double_word<T> two_prod(T a, T b) {
    T p = a * b;
    if constexpr (fma_in_hardware) {
        return {p, std::fma(a, b, -p)};
    } else {
        double_word<T> x = split(a), y = split(b);
        return {p, ((x.hi * y.hi - p) + x.hi * y.lo + x.lo * y.hi) + x.lo * y.lo};
    }
}

// Sum of two double-words, accurate even when they nearly cancel: both the
// high and the low parts are added exactly and the errors are folded back.
template <class T>
inline double_word<T> operator+(double_word<T> x, double_word<T> y) {
    double_word<T> s = two_sum(x.hi, y.hi);
    double_word<T> t = two_sum(x.lo, y.lo);
    s.lo += t.hi;
    s = fast_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return fast_two_sum(s.hi, s.lo);
}

// Sum of two double-words of the same sign: nothing cancels, so the low
// parts can be added together before renormalising (about half the work).
template <class T>
inline double_word<T> add_same_sign(double_word<T> x, double_word<T> y) {
    double_word<T> s = two_sum(x.hi, y.hi);
    s.lo += x.lo + y.lo;
    return fast_two_sum(s.hi, s.lo);
}

template <class T>
inline double_word<T> operator-(double_word<T> x) {
    return {-x.hi, -x.lo};
}

template <class T>
inline double_word<T> operator-(double_word<T> x, double_word<T> y) {
    return x + (-y);
}

template <class T>
inline double_word<T> operator*(double_word<T> x, double_word<T> y) {
    double_word<T> p = two_prod(x.hi, y.hi);
    p.lo += x.hi * y.lo + x.lo * y.hi;
    return fast_two_sum(p.hi, p.lo);
}

template <class T>
inline double_word<T> operator*(double_word<T> x, T y) {
    double_word<T> p = two_prod(x.hi, y);
    p.lo += x.lo * y;
    return fast_two_sum(p.hi, p.lo);
}

// The sum of N numbers as if it were computed with three times the
// precision of T and rounded once (Ogita, Rump and Oishi's SumK, K = 3):
// two sweeps of two_sum push the rounding errors down the array without
// losing any of them, then a plain sum adds what is left. Used where the
// terms cancel to something 10^8 times smaller than themselves.
template <class T, std::size_t N>
inline T sum_k3(std::array<T, N> p) {
    for (int sweep = 0; sweep < 2; ++sweep) {
        for (std::size_t i = 1; i < N; ++i) {
            double_word<T> s = two_sum(p[i], p[i - 1]);
            p[i] = s.hi;
            p[i - 1] = s.lo;
        }
    }
    T sum = 0;
    for (std::size_t i = 0; i + 1 < N; ++i) sum += p[i];
    return sum + p[N - 1];
}

// Scales by 2^k: exact unless the result leaves the range of T.
template <class T>
inline double_word<T> scaled(double_word<T> x, int k) {
    return {std::ldexp(x.hi, k), std::ldexp(x.lo, k)};
}

// The sign of hi + lo, read without rounding them together.
template <class T>
inline bool is_negative(double_word<T> x) {
    return x.hi < 0 || (x.hi == 0 && x.lo < 0);
}

}  // namespace rt
