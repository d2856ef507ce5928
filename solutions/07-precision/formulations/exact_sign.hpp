// exact_sign.hpp — "is this dot product exactly zero?" answered exactly.
//
// A ray is parallel to a plane when d.n = 0, and parallel to a triangle's
// plane (or lying in it, or the triangle is degenerate) when
// d.((b - a) x (c - a)) = 0. Rounded, these quantities can come out as a
// tiny non-zero number although the exact one is 0: with
//     d = (1 + 2^-12, 1 + 2^-12 + 2^-13, 2^-25),  n = (-(1 + 2^-13), 1, 1)
// the exact d.n is 0 but float's is 2^-25, and a "parallel" ray would hit
// the plane at t ~ 3e7. The routines below decide the sign exactly:
//   1. a filter: the plain rounded value, and a bound on its error; when the
//      value is farther from 0 than the bound, its sign is the exact sign
//      (this is the common case and costs a few operations);
//   2. otherwise every product is split into exact pieces (error_free.hpp's
//      two_prod, in double for float data) and the pieces are added into a
//      Shewchuk expansion: a list of non-overlapping numbers whose sum is
//      the exact value, so the sign of its largest piece is the exact sign.
//
// API (T = float, double or long double; all inputs finite):
//   int  exact_dot_sign(a, b)               sign of a.b: -1, 0 or +1, exact
//   int  exact_orientation_sign(d, a, b, c) sign of d.((b - a) x (c - a)), exact
//   bool parallel_exactly(d, n)             d.n == 0 exactly (filter first)
//   bool flat_exactly(d, a, b, c)           d.((b-a) x (c-a)) == 0 exactly
//                                           (filter first): the ray is parallel
//                                           to the triangle's plane, lies in it,
//                                           or the triangle is degenerate
//   int  direction_scale(d)                 k such that 2^k d has its largest
//                                           component near 1 (0 when it already
//                                           is): scaling a subnormal direction
//                                           this way keeps d.d and d.n from
//                                           underflowing; t scales by 2^k.
// Exactness: always for float data (every product of two or three floats,
// and its rounding error, fits double's range). For double and long double
// each vector is first scaled by a power of two (which changes no sign);
// the answer is exact unless a product of scaled components falls below
// the subnormal range, which needs a non-zero component more than 2^-300
// times smaller than its vector's largest component. Non-finite input
// gives 0 ("no decision"; callers reject NaN and infinity beforehand).
//
// Used by the plane and triangle formulations here. tools/render/fast_path.cpp
// (owned by the render helper) should call parallel_exactly in its plane test
// and flat_exactly in its triangle test, and scale a tiny direction with
// direction_scale, so that its answers match the formulations'.
#pragma once

#include "07-precision/error_free.hpp"

#include "common/math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

namespace rt::formulations {

namespace exact_detail {

// The arithmetic of the exact path: double for float data (a float product
// is exact there), T itself otherwise.
template <class T>
using work = std::conditional_t<std::is_same_v<T, float>, double, T>;

// a * b = hi + lo exactly. long double has no Dekker split constant in
// error_free.hpp, so it always uses fma (correctly rounded in glibc).
template <class W>
inline double_word<W> product(W a, W b) {
    if constexpr (std::is_same_v<W, long double>) {
        W p = a * b;
        return {p, std::fma(a, b, -p)};
    } else {
        return two_prod(a, b);
    }
}

// A sum kept exactly as non-overlapping pieces of increasing magnitude
// (Shewchuk's Grow-Expansion with zero elimination). Adding a number runs
// two_sum through the pieces: the sum is never rounded, only re-split.
template <class W, std::size_t N>
struct expansion {
    std::array<W, N> piece{};
    std::size_t count = 0;

    void add(W b) {
        if (b == 0) return;
        std::size_t kept = 0;
        for (std::size_t i = 0; i < count; ++i) {
            double_word<W> s = two_sum(b, piece[i]);
            b = s.hi;
            if (s.lo != 0) piece[kept++] = s.lo;
        }
        if (b != 0) piece[kept++] = b;
        count = kept;
    }
    void add_product(W x, W y) {
        double_word<W> p = product(x, y);
        add(p.lo);
        add(p.hi);
    }
    // x y z: (x y) is exact as hi + lo, each times z exact as hi + lo.
    void add_product(W x, W y, W z) {
        double_word<W> p = product(x, y);
        add_product(p.hi, z);
        if (p.lo != 0) add_product(p.lo, z);
    }
    // The largest piece decides: the others together are smaller than it.
    int sign() const { return count == 0 ? 0 : (piece[count - 1] > 0 ? 1 : -1); }
};

template <class T>
T largest_magnitude(const vec3<T>& v) {
    return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// Scale so that the largest magnitude is in [1, 2): a power of two, exact.
template <class W>
vec3<W> normalised_exponent(const vec3<W>& v, int k) {
    return {std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
}

template <class T>
bool finite(const vec3<T>& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The scale that brings m (> 0) into [1, 2); 0 for float data (not needed).
template <class T>
int exponent_for(T m) {
    if constexpr (std::is_same_v<T, float>) return 0; else return m > 0 ? -std::ilogb(m) : 0;
}

}  // namespace exact_detail

template <class T>
int exact_dot_sign(const vec3<T>& a, const vec3<T>& b) {
    using namespace exact_detail;
    using W = work<T>;
    if (!finite(a) || !finite(b)) return 0;
    vec3<W> x = normalised_exponent(convert<W>(a), exponent_for(largest_magnitude(a)));
    vec3<W> y = normalised_exponent(convert<W>(b), exponent_for(largest_magnitude(b)));
    expansion<W, 8> e;
    e.add_product(x.x, y.x);
    e.add_product(x.y, y.y);
    e.add_product(x.z, y.z);
    return e.sign();
}

// d.((b - a) x (c - a)) = d.(a x b + b x c + c x a): eighteen products of
// three inputs each, no rounded difference anywhere.
template <class T>
int exact_orientation_sign(const vec3<T>& d, const vec3<T>& a, const vec3<T>& b, const vec3<T>& c) {
    using namespace exact_detail;
    using W = work<T>;
    if (!finite(d) || !finite(a) || !finite(b) || !finite(c)) return 0;
    const int kv = exponent_for(std::max({largest_magnitude(a), largest_magnitude(b), largest_magnitude(c)}));
    const vec3<W> D = normalised_exponent(convert<W>(d), exponent_for(largest_magnitude(d)));
    const vec3<W> P[3] = {normalised_exponent(convert<W>(a), kv), normalised_exponent(convert<W>(b), kv),
                          normalised_exponent(convert<W>(c), kv)};
    expansion<W, 80> e;
    for (int i = 0; i < 3; ++i) {
        const vec3<W>& u = P[i];
        const vec3<W>& v = P[(i + 1) % 3];
        // d.(u x v) = dx (uy vz - uz vy) + dy (uz vx - ux vz) + dz (ux vy - uy vx)
        e.add_product(D.x, u.y, v.z), e.add_product(-D.x, u.z, v.y);
        e.add_product(D.y, u.z, v.x), e.add_product(-D.y, u.x, v.z);
        e.add_product(D.z, u.x, v.y), e.add_product(-D.z, u.y, v.x);
    }
    return e.sign();
}

// The filters. A dot product of three terms computed in T is off by at most
// 3u (|a|.|b|) (u = half an ULP of 1), plus, near the subnormals, half the
// smallest subnormal per operation. The bounds below are that, doubled.
template <class T>
bool parallel_exactly(const vec3<T>& d, const vec3<T>& n) {
    const T dn = dot(d, n);
    const T size = std::fabs(d.x * n.x) + std::fabs(d.y * n.y) + std::fabs(d.z * n.z);
    constexpr T u = std::numeric_limits<T>::epsilon() / 2;
    const T bound = T(8) * u * size + T(8) * std::numeric_limits<T>::denorm_min();
    if (std::fabs(dn) > bound) return false;  // certainly not 0 (and not NaN)
    return exact_dot_sign(d, n) == 0;
}

template <class T>
bool flat_exactly(const vec3<T>& d, const vec3<T>& a, const vec3<T>& b, const vec3<T>& c) {
    // Moeller-Trumbore's determinant e1.(d x e2), with e1 and e2 rounded:
    // each rounding is relative to its own term, so the error is at most a
    // small multiple of u times the same expression in absolute values.
    const vec3<T> e1 = b - a, e2 = c - a;
    const T det = dot(e1, cross(d, e2));
    const vec3<T> ad(std::fabs(d.x), std::fabs(d.y), std::fabs(d.z));
    const vec3<T> a1(std::fabs(e1.x), std::fabs(e1.y), std::fabs(e1.z));
    const vec3<T> a2(std::fabs(e2.x), std::fabs(e2.y), std::fabs(e2.z));
    const vec3<T> ac(ad.y * a2.z + ad.z * a2.y, ad.z * a2.x + ad.x * a2.z, ad.x * a2.y + ad.y * a2.x);
    const T size = dot(a1, ac);
    constexpr T u = std::numeric_limits<T>::epsilon() / 2;
    // A product of three that underflows is off by half a subnormal times
    // the third factor: hence the |e1| term.
    const T bound = T(32) * u * size + T(32) * std::numeric_limits<T>::denorm_min() * (T(1) + a1.x + a1.y + a1.z);
    if (std::fabs(det) > bound) return false;
    return exact_orientation_sign(d, a, b, c) == 0;
}

template <class T>
int direction_scale(const vec3<T>& d) {
    const T m = exact_detail::largest_magnitude(d);
    // Comfortable: squares and products with other inputs stay normal.
    static const T low = std::ldexp(T(1), std::numeric_limits<T>::min_exponent / 4);
    static const T high = std::ldexp(T(1), std::numeric_limits<T>::max_exponent / 4);
    if (!(m > 0) || !std::isfinite(m) || (m >= low && m <= high)) return 0;
    return -std::ilogb(m);
}

}  // namespace rt::formulations
