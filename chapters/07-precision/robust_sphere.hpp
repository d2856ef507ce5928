// robust_sphere.hpp — chapter 07's exercise: the sphere test that keeps its digits.
//
// Same question as chapter 02 (where does a ray meet a sphere?), same
// answer for exact arithmetic, but computed so that float still gets it
// right when the sphere is thousands of radii away or huge and close.
// README.md teaches one trap and its fix per section; each fix is one
// function below, in the README's order, with its own public tests:
//
//   step 1  quarter_discriminant   trap 1, a far sphere loses its radius
//   step 2  stable_roots           trap 2, the near root cancels
//   step 3  constant_term          trap 3, c = f.f - r^2 cancels
//   step 4  scaled_offset          traps 4 and 5, a rounded f; squares that under- or overflow
//   step 5  unscaled_root          trap 5 again: back to the caller's units
//   step 6  intersect_sphere_robust, which puts them together.
//
// Your code goes in robust_sphere.cpp; the reference solution implements the
// same declarations. error_free.hpp (given) has the exact sums and products.
#pragma once

#include "error_free.hpp"

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <optional>
#include <type_traits>

namespace rt::ch07 {

// The arithmetic type of the steps: double for float data (every float is a
// double, and the product of two floats is exact in double), T itself for
// double and long double.
template <class T>
using wide = std::conditional_t<std::is_same_v<T, float>, double, T>;

// A ray and a sphere as the steps see them (step 4 makes it; the tests of
// steps 1 and 3 build it directly). Everything is relative to the centre and
// scaled by powers of two, so no digit is lost and no square leaves W's range.
template <class T>
struct scaled_problem {
    double_word<wide<T>> f[3];  // f = o - C, exactly (f[k].hi + f[k].lo), times 2^ef
    wide<T> d[3] = {0, 0, 0};   // the direction, times 2^ed
    wide<T> radius = 0;         // the radius, times 2^ef
    int ef = 0;                 // f and the radius were multiplied by 2^ef,
    int ed = 0;                 // the direction by 2^ed: t = t' 2^(ed - ef)
};

// The quadratic a t'^2 + 2 half_b t' + c = 0 of a scaled problem, its
// coefficients as pairs (hi + lo: about twice W's digits).
template <class T>
struct quadratic {
    double_word<wide<T>> a;             // d.d
    double_word<wide<T>> half_b;        // f.d
    double_word<wide<T>> quarter_disc;  // half_b^2 - a c, the discriminant / 4
};

// The two roots of a quadratic, ordered: near <= far.
template <class T>
struct root_pair {
    wide<T> near = 0, far = 0;
};

// Step 1 (README, "Fix 1"): the coefficients a = d.d, half_b = f.d and the
// quarter discriminant, all from p's exact pieces, as pairs. The quarter
// discriminant is computed through the perpendicular distance, by
// Lagrange's identity
//     quarter_disc = a r^2 - |f x d|^2      (|f x d| / |d|: the centre's distance from the line),
// with every product split exactly (two_prod) and every sum kept as a pair:
// it never subtracts two squares that agree in most of their digits, so its
// sign is right for a far sphere and for a ray a few ULPs from tangency.
// Not half_b^2 - a c, and not f.f - half_b^2 / a (Pythagoras: squares first).
template <class T>
quadratic<T> quarter_discriminant(const scaled_problem<T>& p);

// Step 2 (README, "Fix 2"): the roots of a t^2 + 2 half_b t + c = 0 from the
// stable pair, for quarter_disc >= 0 and a > 0:
//     q = -(half_b + sign(half_b) sqrt(quarter_disc)),   roots c / q and q / a,
// where sign(half_b) is the sign bit of half_b (std::copysign), so q adds two
// numbers of the same sign. Returned ordered (which of c / q and q / a is
// nearer depends on the sign of half_b). q = 0 (half_b = 0 and a zero
// discriminant: the origin touches the sphere) gives the double root 0.
// T is not deduced: call it as stable_roots<T>(...).
template <class T>
root_pair<T> stable_roots(wide<T> a, wide<T> half_b, wide<T> c, wide<T> quarter_disc);

// Step 3 (README, "Fix 3"): c = f.f - radius^2 of a scaled problem, accurate
// even when f.f and radius^2 agree in nearly every digit (an origin on the
// surface of a huge sphere): the exact pieces of the squares,
// (hi + lo)^2 = hi^2 + 2 hi lo + lo^2 with hi^2, 2 hi lo and radius^2 split
// by two_prod, added as if in three times W's precision (sum_k3) and
// rounded once. Within 2 ULPs of W of the exact c of p.
template <class T>
wide<T> constant_term(const scaled_problem<T>& p);

// Step 4 (README, "Fix 4" and "Fix 5"): the problem of step 1 from the
// caller's sphere and ray, with no rounding at all:
//   * f = o - C exactly, each component a pair from two_sum;
//   * f and the radius scaled together by 2^ef, the direction on its own by
//     2^ed (powers of two: exact), so that squares and products of four of
//     them neither overflow nor sink into the subnormals; ef = ed = 0 while
//     everything is in a comfortable range (about 2^-200..2^200 in double);
//   * inputs within a factor 4 of W's largest number are quartered before
//     the two-sum, so that o - C stays finite, and the -2 counted into ef.
// Requires finite inputs, a positive radius and a direction that is not all
// zeros (intersect_sphere_robust checks them first).
template <class T>
scaled_problem<T> scaled_offset(const sphere<T>& s, const ray<T>& r);

// Step 5 (README, "Fix 5"): a root t' of the scaled problem in the caller's
// units, t = t' 2^exponent (exponent = ed - ef), rounded to T once. Beyond
// T's range: infinite (the range test rejects it), except that a root
// computed a few ULPs above T's largest number (the roots are a rounding or
// two off) is that largest number.
// T is not deduced: call it as unscaled_root<T>(...).
template <class T>
T unscaled_root(wide<T> t_scaled, int exponent);

// Step 6: intersect_sphere_robust, the steps put together.
//
// Inputs
//   s      a sphere: centre s.center, radius s.radius. A radius that is not
//          positive (zero, negative or NaN) describes no sphere: a miss.
//   r      a ray r(t) = r.origin + t * r.direction; the direction need not be
//          unit length. A zero direction (all components 0) is a miss; a
//          tiny, even subnormal, direction is not zero.
//   range  the open interval (range.min, range.max) of acceptable t.
//
// Returns (the same contract as ch02::intersect_sphere)
//   the hit with the smallest t in (range.min, range.max), or std::nullopt:
//     t       the ray parameter: the nearer root if it is in range, else the
//             farther root if that is in range (e.g. the origin is inside)
//     point   r.at(t)
//     normal  the outward unit normal at the hit, (point - s.center) / radius,
//             computed from the centre-relative vector f + t d (README,
//             "The normal, and the whole test")
//     object  left at -1
//   A tangent ray (one double root) is a hit. Never a NaN or infinite t:
//   NaN or infinity in any input is a miss.
//
// The numerical promise (README, "What is left"), for every finite input
// (float, double, long double):
//   * hit or miss is decided correctly unless a change of one ULP in some
//     input would change it (a ray within an ULP or so of tangency);
//   * a hit's t is within 4 ULPs of the exact root of the rounded inputs
//     (the study and tests/numerics measure at most 3 in double and 0 in
//     float), tangent rays and rays starting on the surface included;
//   * tiny and huge spheres (radius 1e-30 or 1e30 in float, 1e-200 or 1e200
//     in double) and non-zero subnormal directions are answered like any
//     other: a direction is zero only when all its components are 0.
//
// T is float, double or long double (--error measures with
// your long double version at some sizes): the same code is compiled for all three.
template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch07
