// robust_sphere.hpp — chapter 07's exercise: the sphere test that keeps its digits.
//
// Same question as chapter 02 (where does a ray meet a sphere?), same
// answer for exact arithmetic, but computed so that float still gets it
// right when the sphere is thousands of radii away or huge and close.
// README.md explains each step; this header is the contract. Your code goes
// in robust_sphere.cpp, and the reference solution implements exactly the
// same declaration.
#pragma once

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <optional>

namespace rt::ch07 {

// intersect_sphere_robust
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
//     normal  the outward unit normal at the hit, (point - s.center) / radius
//             (see README: computed from the centre-relative vector)
//     object  left at -1
//   A tangent ray (one double root) is a hit. Never a NaN or infinite t:
//   NaN or infinity in any input is a miss.
//
// The numerical promise (README.md, "three places where digits vanish" and
// "Exact pieces and powers of two").
// With f = r.origin - s.center, a = d.d and half_b = f.d, for every finite
// input (float, double, long double):
//   * hit or miss is decided correctly unless a change of one ULP in some
//     input would change it (a ray within an ULP or so of tangency);
//   * a hit's t is within 4 ULPs of the exact root of the rounded inputs,
//     tangent rays and rays starting on the surface included;
//   * tiny and huge spheres (radius 1e-30 or 1e30 in float, 1e-200 or 1e200
//     in double) and non-zero subnormal directions are answered like any
//     other: a direction is zero only when all its components are 0.
// It takes these steps:
//   0. f = o - C exactly, as a pair hi + lo (two-sum). Then powers of two
//      scale f and the radius together, and d on its own, so that no
//      square overflows or underflows; t = t' 2^(ed - ef) undoes it.
//      (Inputs within a factor 4 of the largest W are quartered before the
//      two-sum, so that o - C itself stays finite.)
//   1. The discriminant through the perpendicular distance, subtracted
//      BEFORE squaring: disc/4 = a r^2 - |f x d|^2 (|f x d| / |d| is the
//      length of the foot vector f - (half_b / a) d), with every product
//      split into exact pieces (fma) and kept as pairs.
//      Not f.f - (f.d)^2 / a, which subtracts after squaring.
//   2. The roots come from the stable pair
//          q = -(half_b + sign(half_b) sqrt(discriminant / 4)),
//          roots  c / q  and  q / a,
//      in which sign(half_b) makes the sum add two numbers of the same sign,
//      so neither root is a difference of nearly equal numbers.
//   3. c = f.f - radius^2 keeps the low halves of its squares (exact
//      products through fma) and adds all pieces with a compensated sum,
//      so a huge sphere seen from close by, where f.f and radius^2 agree in
//      almost every digit, still has an accurate c.
//   For float data, all of this may be done in double (every float is a
//   double): the reference solution does that.
//
// T is float, double or long double (the chapter program uses long double as
// its reference): the same code is compiled for all three.
template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch07
