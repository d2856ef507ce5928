// plane.hpp — chapter 04's exercise: a ray against an infinite plane.
//
// A plane is every point x with  (x - p0) . n = 0  (a point p0 on it and a
// normal n). Substituting the ray gives one linear equation in t, so there
// is at most one crossing. This header is the contract; your code goes in
// plane.cpp, and the reference solution implements the same declaration.
#pragma once

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <optional>

namespace rt::ch04 {

// intersect_plane
//
// Inputs
//   p      a plane through p.point with normal p.normal (not necessarily unit, never zero;
//          any finite length, even one whose square overflows or underflows T,
//          such as 1e30 or 1e-30 in float: normalise without squaring first)
//   r      a ray r(t) = r.origin + t * r.direction
//   range  the open interval (range.min, range.max) of acceptable t
//
// Returns
//   the hit if its t lies in (range.min, range.max), else std::nullopt:
//     t       ray parameter of the crossing
//     point   r.at(t)
//     normal  the plane's own normal p.normal / |p.normal|, from either
//             side: this is the plane's outward side. A ray from behind
//             (d . n > 0) gets the same normal; hit.front_face(r) is then
//             false and hit.facing_normal(r) the negative, so it is shaded
//             like a plane hit from the front (common/hit_record.hpp: one
//             rule for every shape)
//     object  left at -1
//   A ray parallel to the plane (including one lying in it) is a miss: never
//   a NaN, never an infinity, never a division by zero that passes as a hit.
//   Parallel means that d.n, as computed in T, is 0: a tiny non-zero d.n is a
//   genuine, far hit. (When the products d_i n_i need more digits than T has,
//   a d.n that is exactly 0 can round to a tiny number; then the answer may be
//   a hit at an enormous t, or, for a ray lying in the plane, at a point of
//   the ray, which is on the plane. Deciding those exactly is chapter 07's
//   subject; the tests do not ask it here.)
//   A direction with tiny, even subnormal, components is not zero: the
//   reference solution scales it by a power of two before taking d.n (t
//   scales back exactly), so its d.n keeps its digits. The tests do not ask
//   it; without the scaling such a ray may be a miss or a far-off t.
template <class T>
std::optional<hit_record<T>> intersect_plane(const plane<T>& p, const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch04
