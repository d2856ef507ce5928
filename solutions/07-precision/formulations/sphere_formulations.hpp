// sphere_formulations.hpp — seven ways to intersect a ray with a sphere.
//
// All of them solve the same quadratic. With f = origin - center,
//     |f + t d|^2 = r^2   <=>   a t^2 + 2 h t + c = 0,
//     a = d.d,  h = f.d,  c = f.f - r^2,
// and they differ only in the order of the floating-point operations. That
// order decides whether the answer keeps its digits when the sphere is far
// away (|f| >> r), huge and close (c is tiny next to f.f), or grazed (the
// discriminant is tiny next to its terms).
//
// Every routine has the contract of the course's sphere exercises: the
// smallest t with range.min < t < range.max, or std::nullopt; never NaN,
// never infinity, never a t outside the range. The direction need not be
// unit length; a zero direction is a miss. Forms 1 to 5 compute d.d
// plainly, so a non-zero direction whose d.d underflows to 0 (components
// below about 1e-23 in float, 1e-162 in double) is treated as zero: a
// miss. The compensated and mixed forms scale such a direction by a power
// of two and answer it like any other.
// What forms 1 to 5 do not check (they are the textbook formulas, measured
// as they are): a zero or negative radius is used as given (r^2 makes it a
// sphere: a hit), and squares outside T's range are not avoided: above
// about 1e19 in float, 1e154 in double (|f| or r) they overflow and the ray
// is missed; below about 1e-19 and 1e-154 they underflow and hits are lost
// or t has few correct digits. Never a NaN answer. The compensated form
// (and so the mixed form in double) quarters o, C and r when one of them is
// above a quarter of T's largest number, so that o - C cannot overflow.
#pragma once

#include "07-precision/error_free.hpp"

#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace rt::formulations {

// The nearer root inside the range. A NaN root fails surrounds() and is
// dropped, so no formulation can hand a NaN on as a hit.
template <class T>
std::optional<T> nearest_in_range(T t0, T t1, const interval<T>& range) {
    if (t1 < t0) std::swap(t0, t1);
    if (range.surrounds(t0)) return t0;
    if (range.surrounds(t1)) return t1;
    return std::nullopt;
}

// 1. The textbook quadratic: b = 2 f.d, discriminant b^2 - 4ac.
// Two traps: c = f.f - r^2 cancels when |f| >> r (a unit sphere 4096 units
// away leaves c with no correct digit in float), and -b + sqrt(disc)
// cancels for the far root.
template <class T>
std::optional<T> sphere_plain(const ray<T>& ray_, const sphere<T>& s, const interval<T>& range) {
    vec3<T> f = ray_.origin - s.center;
    T a = dot(ray_.direction, ray_.direction);
    T b = T(2) * dot(f, ray_.direction);
    T c = dot(f, f) - s.radius * s.radius;
    T disc = b * b - T(4) * a * c;
    if (!(disc >= 0)) return std::nullopt;
    T root = std::sqrt(disc);
    return nearest_in_range((-b - root) / (T(2) * a), (-b + root) / (T(2) * a), range);
}

// 2. The same with h = f.d (half of b): fewer operations, the same traps.
template <class T>
std::optional<T> sphere_half_b(const ray<T>& ray_, const sphere<T>& s, const interval<T>& range) {
    vec3<T> f = ray_.origin - s.center;
    T a = dot(ray_.direction, ray_.direction);
    T h = dot(f, ray_.direction);
    T c = dot(f, f) - s.radius * s.radius;
    T disc = h * h - a * c;
    if (!(disc >= 0)) return std::nullopt;
    T root = std::sqrt(disc);
    return nearest_in_range((-h - root) / a, (-h + root) / a, range);
}

// 3. The geometric form: with a unit direction u, the centre projects onto
// the ray at tca = (C - o).u; the squared distance of the centre from the
// ray is d2 = |C - o|^2 - tca^2 (Pythagoras), a hit needs d2 <= r^2, and
// the chord is 2 sqrt(r^2 - d2). d2 is the difference of two huge numbers
// when the sphere is far: the same cancellation as c, in a new place.
template <class T>
std::optional<T> sphere_geometric(const ray<T>& ray_, const sphere<T>& s, const interval<T>& range) {
    T len = length(ray_.direction);
    vec3<T> u = ray_.direction / len;
    vec3<T> to_center = s.center - ray_.origin;
    T tca = dot(to_center, u);
    T d2 = dot(to_center, to_center) - tca * tca;
    T r2 = s.radius * s.radius;
    if (!(d2 <= r2)) return std::nullopt;
    T thc = std::sqrt(r2 - d2);
    return nearest_in_range((tca - thc) / len, (tca + thc) / len, range);
}

// 4. Hearn and Baker's discriminant (Ray Tracing Gems, chapter 7): the
// discriminant equals a (r^2 - |l|^2) where l = f - (h/a) d is the vector
// from the centre to the ray's closest point. |l| is small next to |f|,
// so r^2 - l.l no longer subtracts two huge numbers. The roots still use
// the textbook -h -/+ sqrt(disc).
template <class T>
std::optional<T> sphere_rtg_discriminant(const ray<T>& ray_, const sphere<T>& s, const interval<T>& range) {
    const vec3<T>& d = ray_.direction;
    vec3<T> f = ray_.origin - s.center;
    T a = dot(d, d);
    T h = dot(f, d);
    vec3<T> l = f - (h / a) * d;
    T disc = a * (s.radius * s.radius - dot(l, l));
    if (!(disc >= 0)) return std::nullopt;
    T root = std::sqrt(disc);
    return nearest_in_range((-h - root) / a, (-h + root) / a, range);
}

// The stable root pair: q = -(h + sign(h) sqrt(disc)) adds two numbers of
// the same sign, so nothing cancels, and the roots are c/q and q/a (their
// product is c/a, Vieta). q = 0 only when h = 0 and disc = 0: a double root
// at 0.
template <class T>
std::pair<T, T> stable_roots(T a, T h, T c, T disc) {
    T q = -(h + std::copysign(std::sqrt(disc), h));
    if (q == 0) return {T(0), T(0)};
    return {c / q, q / a};
}

// 5. Ray Tracing Gems' combined form: Hearn and Baker's discriminant with
// the stable root pair. What is left: f = o - C itself is rounded, and
// c = f.f - r^2 still cancels, so the near root c/q is poor on a huge
// sphere seen from close by, and l = f - (h/a) d cancels in a general
// direction when the sphere is far.
template <class T>
std::optional<T> sphere_rtg_stable(const ray<T>& ray_, const sphere<T>& s, const interval<T>& range) {
    const vec3<T>& d = ray_.direction;
    vec3<T> f = ray_.origin - s.center;
    T a = dot(d, d);
    T h = dot(f, d);
    vec3<T> l = f - (h / a) * d;
    T r2 = s.radius * s.radius;
    T disc = a * (r2 - dot(l, l));
    if (!(disc >= 0)) return std::nullopt;
    auto [t0, t1] = stable_roots(a, h, dot(f, f) - r2, disc);
    return nearest_in_range(t0, t1, range);
}

namespace detail {
// Rounds a double root to float; beyond the float range it becomes infinite
// (and fails the range test) instead of an undefined conversion.
inline float to_float(double t) {
    constexpr double top = std::numeric_limits<float>::max();
    return std::fabs(t) <= top ? static_cast<float>(t) : std::copysign(infinity<float>, static_cast<float>(t));
}

// c = f.f - r^2 for float data from exact pieces (f = o - C by two_sum, the
// squares split, the sum in triple precision): chapter 07's steps 4 and 3,
// the reference solution's own code (chapter07_reference.cpp).
double constant_term_of_floats(const vec3<float>& o, const sphere<float>& s);
}  // namespace detail

// 6. The compensated form is chapter 07's reference solution,
// intersect_sphere_robust (solutions/07-precision/robust_sphere.cpp, one
// function per step of the lecture; compiled for the study by
// chapter07_reference.cpp): every quantity that cancels is carried as a
// pair (error_free.hpp), so it keeps twice the digits of the arithmetic,
// which is double for float data and T otherwise:
//   * f = o - C is exact (two_sum), so a ray origin 0.01 above a sphere of
//     radius 10^6 does not lose its height before any arithmetic starts;
//   * f and d are scaled by powers of two, so no square under- or overflows
//     (a subnormal direction is a direction);
//   * the discriminant is a r^2 - |f x d|^2 (Lagrange's identity), every
//     product split exactly (two_prod), summed as pairs;
//   * c = f.f - r^2 is summed from its exact pieces in triple precision.
// The roots come from the stable pair, so each is within a few ULPs.
template <class T>
std::optional<T> sphere_compensated(const ray<T>& ray_, const sphere<T>& s, const interval<T>& range);

namespace detail {
// The roots of the stable pair, rounded to float once, the near one first:
// for h < 0 (q > 0) c/q <= q/a, for h >= 0 (q < 0) q/a <= c/q. Needs
// disc > 0 (so q != 0). Used for ranges that start before 0.
inline std::optional<float> near_root_first(double a, double h, double c, double disc, const interval<float>& range) {
    const double q = -(h + std::copysign(std::sqrt(disc), h));
    const bool c_first = h < 0;
    const float near = to_float(c_first ? c / q : q / a);
    if (range.surrounds(near)) return near;
    const float far = to_float(c_first ? q / a : c / q);
    if (range.surrounds(far)) return far;
    return std::nullopt;
}

// The answer for a range that starts at 0 or later (every ray a renderer
// casts), with one division. Needs disc >= 0.
//
// The roots are c/q and q/a with q = -(h + sign(h) sqrt(disc)), and their
// signs alone say which one can be the answer: q has the sign of -h, and
// c/q * q/a = c/a has the sign of c.
//   h < 0, c > 0 (outside, heading in): both ahead, c/q is the nearer;
//   h < 0, c <= 0 (inside, or on the surface heading in): c/q <= 0 is
//     behind, q/a is the crossing ahead;
//   h >= 0 (heading out): q/a <= 0 is behind, c/q is ahead only if c < 0.
// So the candidate is q/a when h < 0 and c <= 0, and c/q otherwise: a ray
// leaving a surface from just inside (a refraction ray, or a reflection
// ray whose origin rounded inside) needs no second division. Only when the
// nearer root c/q lies before range.min (an origin outside, range.min > 0)
// can the far root q/a be the answer.
inline std::optional<float> root_ahead(double a, double h, double c, double disc, const interval<float>& range) {
    // signbit, not h < 0: copysign gives h = -0 the sign of a negative h.
    const bool negative_h = std::signbit(h);
    const double q = -(h + std::copysign(std::sqrt(disc), h));
    const bool take_far = negative_h && c <= 0;
    const float t = to_float(take_far ? q / a : c / q);
    if (range.surrounds(t)) return t;
    if (negative_h && c > 0) {
        const float far = to_float(q / a);
        if (range.surrounds(far)) return far;
    }
    return std::nullopt;
}

// c from exact pieces, for the rare origin that c_near_surface cannot
// settle (within about 2^-46 of its terms of the surface, or overflowing in
// float): chapter 07's constant term (constant_term_of_floats). Out of line
// and cold: the common path stays small.
[[gnu::noinline, gnu::cold]] inline double c_from_exact_pieces(const vec3<float>& o, const sphere<float>& s) {
    return constant_term_of_floats(o, s);
}

// c = f.f - r^2 for the origins nearest the surface, where even
// c_near_surface (below) cannot vouch for its digits (about 7% of the
// study's shadow rays leaving a sphere of radius 1e6). It is rebuilt from the
// floats, where every product is exact:
//   * each f_j = o_j - C_j is split into two floats, F_j + L_j (two_sum in
//     float: exact, whatever the exponents);
//   * with k the axis where |F| is largest,
//       c = F_i^2 + F_j^2 + 2 F_k L_k + (|F_k| - r)(|F_k| + r)
//           + (2 F_i + L_i) L_i + (2 F_j + L_j) L_j + L_k^2.
//     A float times a float is exact in double (48 bits); |F_k| - r is
//     exact in float (Sterbenz: near the surface |F_k| is within a factor
//     2 of r) and |F_k| + r in double (26 bits), so their product (50
//     bits) is exact too. The first four terms are large and cancel: they
//     are added with two_sum, which loses nothing; the last three are about
//     2^-23 of them, so their own rounding is far below c.
// What is left is about 2 rounding errors of c and 2^-74 of the terms, so
// c is within 2^-26 of itself whenever |c| >= 2^-46 of the terms; only
// origins closer still (and float overflow) are summed from exact pieces.
[[gnu::noinline]] inline double c_from_floats(const vec3<float>& o, const sphere<float>& s) {
    double_word<float> F[3];
    for (int j = 0; j < 3; ++j) F[j] = two_sum(o[j], -s.center[j]);
    const float ax = std::fabs(F[0].hi), ay = std::fabs(F[1].hi), az = std::fabs(F[2].hi);
    const int k = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    const int i = k == 2 ? 0 : k + 1, j = i == 2 ? 0 : i + 1;
    auto square = [](float x) { return double(x) * x; };
    const float r = s.radius, Fk = std::fabs(F[k].hi);
    const double pair = double(Fk - r) * (double(Fk) + double(r));
    const double cross_k = 2.0 * F[k].hi * F[k].lo;
    const double_word<double> rest = two_sum(square(F[i].hi), square(F[j].hi));
    const double_word<double> big = two_sum(rest.hi, cross_k);
    const double small = (2.0 * F[i].hi + F[i].lo) * F[i].lo + (2.0 * F[j].hi + F[j].lo) * F[j].lo + square(F[k].lo);
    const double c = (big.hi + pair) + ((rest.lo + big.lo) + small);
    if (std::fabs(c) >= 0x1p-46 * (rest.hi + std::fabs(cross_k) + std::fabs(pair))) return c;  // NaN: false
    return c_from_exact_pieces(o, s);
}

// The two parts of c = f.f - r^2 split at the axis k where |f| is largest:
// rest, the sum of the other two squares (the smallest of the three sums
// of two squares: no branch picks k), and pair = (|f_k| - r)(|f_k| + r).
struct largest_axis_parts {
    double rest, pair;
};
[[gnu::always_inline]] inline largest_axis_parts split_at_largest_axis(const vec3<double>& f, double r) {
    const double x2 = f.x * f.x, y2 = f.y * f.y, z2 = f.z * f.z;
    const double rest = std::min(std::min(y2 + z2, x2 + z2), x2 + y2);
    const double big = std::max(std::max(std::fabs(f.x), std::fabs(f.y)), std::fabs(f.z));
    return {rest, (big - r) * (big + r)};
}

// c = f.f - r^2 for an origin near the surface, where the plain sum of
// squares has cancelled (second stage). With k the axis where |f| is
// largest,
//     c = (sum of the other two squares) + (|f_k| - r)(|f_k| + r),
// so the ground sphere's huge f_k meets r in a subtraction of two doubles
// (exact by Sterbenz's lemma when they are within a factor of 2) before
// anything is squared (split_at_largest_axis). What f = o - C lost in
// double (its two_sum error, lo) enters to first order, 2 f.lo.
// Each part is off by at most about 2 double rounding errors of its own
// size (2^-52 of rest + |pair|); the result is used when that stays below
// 2^-25 of c (1 ULP of the float t at most), i.e. |c| >= 2^-27 (rest +
// |pair|). Exactly-computed parts (an origin exactly on the surface: c = 0
// with no error at all) pass too. Only the rest (origins within about 2^-27
// of the surface in units of the farthest coordinate) is computed again
// from the floats (c_from_floats), unless only the sign of c matters
// (out_of_range_sign: a c of that sign puts the root c/q outside the
// range). Its usual case, f exact (lo = 0: the terms in lo vanish), is
// c_near_surface_usual (below), inline in sphere_in_double; this version
// runs for an inexact f.
[[gnu::noinline]] inline double c_near_surface(const vec3<float>& o, const sphere<float>& s, double out_of_range_sign) {
    const vec3<float>& C = s.center;
    const vec3<double> f = convert<double>(o) - convert<double>(C);
    const double r = s.radius;
    const double lx = two_diff_error(double(o.x), double(C.x), f.x), ly = two_diff_error(double(o.y), double(C.y), f.y),
                 lz = two_diff_error(double(o.z), double(C.z), f.z);
    const auto [rest, pair] = split_at_largest_axis(f, r);
    const double lost = 2 * (f.x * lx + f.y * ly + f.z * lz);
    const double c = (rest + lost) + pair;
    // Bounds of the error: 2^-51 (rest + |pair|) from the roundings, 2^-51 |lost|
    // from lost's own rounding, lo.lo (left out) at most (|lx| + |ly| + |lz|)^2.
    const double lo_sum = std::fabs(lx) + std::fabs(ly) + std::fabs(lz);
    const double lo2 = lo_sum * lo_sum;
    if (0x1p-27 * (rest + std::fabs(pair)) + 0x1p-26 * std::fabs(lost) + 0x1p25 * lo2 <= std::fabs(c)) return c;
    // Only c's sign matters when it puts the root c/q behind the range (a
    // shadow ray leaving a surface from a hair outside it): then a c whose
    // sign is certain will do.
    if (out_of_range_sign * c > 0x1p-49 * (rest + std::fabs(pair) + std::fabs(lost)) + 2 * lo2) return c;
    return c_from_floats(o, s);
}

// Two doubles in one SSE2 register (every x86-64 has SSE2): the x and y
// lanes of one step, computed by one instruction.
typedef double double2 __attribute__((vector_size(16)));

// c_near_surface's usual case, inline in sphere_in_double: f = o - C exact
// in double (a difference of two floats always is, unless their exponents
// are more than about 29 apart). Shadow and reflection rays leaving a sphere
// all come here, so it is written for speed:
//   * f's exactness is checked with two_diff_error, two components at a
//     time, and the squares of the errors added (the error of a difference
//     of floats is a multiple of 2^-149, so its square is never 0);
//   * the barrier makes the compiler load o and C again rather than keep
//     them in registers all the way from the top of sphere_in_double, which
//     would cost every other ray a few spills.
// An f that is not exact goes to c_near_surface; a c whose digits
// rest + pair cannot vouch for is computed again by c_from_floats.
[[gnu::always_inline]] inline double c_near_surface_usual(const vec3<float>& o, const sphere<float>& s,
                                                         const vec3<double>& f, double out_of_range_sign) {
    asm volatile("" ::: "memory");
    const vec3<float>& C = s.center;
    const double2 o_xy = {double(o.x), double(o.y)}, C_xy = {double(C.x), double(C.y)}, f_xy = {f.x, f.y};
    const double2 l_xy = two_diff_error(o_xy, C_xy, f_xy);
    const double lz = two_diff_error(double(o.z), double(C.z), f.z);
    const double2 l_xy2 = l_xy * l_xy;
    if (l_xy2[0] + l_xy2[1] + lz * lz != 0) return c_near_surface(o, s, out_of_range_sign);
    const auto [rest, pair] = split_at_largest_axis(f, s.radius);
    const double size = rest + std::fabs(pair), c = rest + pair;
    if (0x1p-27 * size <= std::fabs(c) || out_of_range_sign * c > 0x1p-49 * size) return c;
    return c_from_floats(o, s);
}

// The discriminant as a r^2 - |f x d|^2 (Lagrange's identity: |f x d|^2 =
// a f.f - h^2), which keeps its digits where h^2 - a c cancels (a far
// sphere, a ray near tangency). It is trusted when it is at least 2^-26 of
// a r^2 (its rounding error is a few 2^-53 of a r^2), or below -2^-40 a r^2
// (a certain miss). Anything between is a ray within a hair of tangency:
// *grazing is set, and the caller hands the ray to chapter 07's robust
// test (sphere_compensated), which decides it from exact pieces. NaN (an infinite direction) is a miss.
inline double disc_by_cross(const vec3<double>& f, const vec3<double>& d, double a, double r2, bool* grazing) {
    const vec3<double> g = cross(f, d);
    const double ar2 = a * r2;
    const double disc = ar2 - dot(g, g);
    *grazing = disc < ar2 * 0x1p-26 && disc >= -ar2 * 0x1p-40;
    return disc;
}

// Float inputs, double arithmetic: a product of two floats is exact in
// double and a difference of two floats almost always is, so f, h = f.d and
// c = f.f - r^2 lose (almost) nothing; the roots are rounded to float once,
// at the end.
//
// Two quantities can cancel beyond double's reserve, and each has its own
// remedy:
//   * c, for an origin on or near the surface (a secondary ray, or 1e-3
//     above a sphere of radius 1e7): c_near_surface_usual, and
//     c_near_surface or c_from_floats for the rare origins it cannot settle;
//   * the discriminant h^2 - a c, when a c is close to h^2 (a far sphere, a
//     ray near tangency): a r^2 - |f x d|^2 instead (disc_by_cross), and
//     chapter 07's test for a ray within a hair of tangency (sphere_compensated).
// Whenever c < 0 (the origin inside: a sum of two positive terms) or
// 2 a c <= h^2 (an origin near the surface, not near tangency), h^2 - a c
// does not cancel; that is the path of shadow, reflection and refraction
// rays. Only rays that need more take a slower path, so the common case
// costs little more than the plain float form. Always inlined: GCC would
// otherwise call it, and the call costs as much as a third of the plain
// float test.
[[gnu::always_inline]] inline std::optional<float> sphere_in_double(const ray<float>& ray_, const sphere<float>& s,
                                                                    const interval<float>& range) {
    if (!(s.radius > 0)) return std::nullopt;
    const vec3<double> d = convert<double>(ray_.direction);
    const vec3<double> f = convert<double>(ray_.origin) - convert<double>(s.center);
    const double r2 = double(s.radius) * s.radius;  // exact: a float squared
    const double a = dot(d, d), h = dot(f, d), ff = dot(f, f);
    // No test of every input (ten comparisons on every ray): NaN and
    // infinity make c or the discriminant NaN, and the tests below and
    // root_ahead reject those; off the common path they are rejected
    // explicitly.
    if (!(a > 0)) return std::nullopt;
    double c = ff - r2, disc = 0;
    const bool ahead_only = range.min >= 0;
    bool grazing = false;
    if (c >= 0x1p-22 * ff) {
        // Outside, clearly (the common case): c is off by at most about
        // 6 * 2^-53 f.f (f = o - C by 2^-53 of each component, each square
        // and sum by 2^-53 of its size), at most 2^-28 of itself. Leaving
        // (h >= 0): the roots c/q and q/a are both <= 0. Should the exact h
        // be < 0 while the computed one is >= 0, |h| is below h's rounding
        // error (2^-50 |f| |d|) and the exact discriminant h^2 - a c <
        // 2^-100 a f.f - 2^-23 a f.f is negative: a miss all the same.
        if (h >= 0 && ahead_only) return std::nullopt;
        // h^2 - a c first (two products, where the cross product takes
        // twelve operations): it is off by at most about 19 * 2^-53 a f.f (h
        // by 4 2^-53 |f| |d|, c as above, and both h^2 and a c are at most
        // a f.f). When it is at least 2^-21 a f.f that is below 2^-27.7 of
        // it, and when it is below -2^-48 a f.f the ray surely misses. In
        // between (a far sphere, whose discriminant is tiny next to a f.f,
        // or a ray near tangency) it has cancelled, and the discriminant is
        // computed again from f x d.
        disc = h * h - a * c;
        if (!(disc >= 0x1p-21 * a * ff)) {
            if (disc < -0x1p-48 * a * ff) return std::nullopt;
            disc = disc_by_cross(f, d, a, r2, &grazing);
        }
    } else {
        // NaN or infinity in d, o or C (c is NaN, or d is infinite). a and
        // f.f of float inputs cannot overflow in double.
        if (!(a + ff < infinity<double>)) return std::nullopt;
        // Within about 2^-22 |f| of the surface, or inside. c is off by at
        // most 6 * 2^-53 f.f, below 2^-25 of c (at most 1 ULP of the float
        // t) when |c| >= 2^-27 f.f; only origins nearer the surface need
        // c_near_surface_usual. It returns c within 2^-26 of itself or, when
        // its sign puts the root c/q behind the range (q has the sign of -h),
        // a c of certain sign.
        if (!(std::fabs(c) >= 0x1p-27 * ff))
            c = c_near_surface_usual(ray_.origin, s, f, ahead_only ? (h >= 0 ? 1.0 : -1.0) : 0.0);
        // Inside, clearly (h^2 - a c is a sum of two positive terms), or not
        // near tangency: a |c| <= 2^-22 a f.f <= h^2 / 4, so h^2 - a c does
        // not cancel, and h is within 2^-40 of itself.
        if (c <= -0x1p-22 * ff || h * h >= 0x1p-20 * a * ff) {
            if (c >= 0 && h >= 0 && ahead_only) return std::nullopt;  // leaving from outside (or from t = 0)
            disc = h * h - a * c;
        } else {
            disc = disc_by_cross(f, d, a, r2, &grazing);
        }
    }
    // A grazing ray: the discriminant cancelled more than 26 of double's 53
    // bits, too few left for float's 24. Chapter 07's test computes it again
    // from exact pieces (out of line: the common path stays small).
    if (grazing) return sphere_compensated(ray_, s, range);
    if (!(disc >= 0)) return std::nullopt;  // a miss, or NaN
    if (ahead_only) return root_ahead(a, h, c, disc, range);
    return near_root_first(a, h, c, disc, range);
}
}  // namespace detail

// 7. The mixed-precision form: the arithmetic is wider than the data. For
// float data that is double arithmetic (detail::sphere_in_double); for
// double data it is double-double, which is exactly what the compensated
// form computes, so the double case calls it.
template <class T>
[[gnu::always_inline]] inline std::optional<T> sphere_mixed(const ray<T>& ray_, const sphere<T>& s, const interval<T>& range) {
    if constexpr (sizeof(T) == sizeof(float))
        return detail::sphere_in_double(ray_, s, range);
    else
        return sphere_compensated(ray_, s, range);
}

}  // namespace rt::formulations
