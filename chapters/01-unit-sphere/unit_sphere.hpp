// unit_sphere.hpp — chapter 01's exercise: where does a ray meet the unit sphere?
//
// The unit sphere is every point p with  p . p = 1  (distance 1 from the
// origin). This header is the contract; your code goes in unit_sphere.cpp,
// and the reference solution implements exactly the same declaration.
#pragma once

#include "common/interval.hpp"
#include "common/ray.hpp"

#include <optional>

namespace rt::ch01 {

// intersect_unit_sphere
//
// Inputs
//   r      a ray  r(t) = r.origin + t * r.direction. The direction need not be
//          unit length (a pinhole camera's is not); it is never asked to be zero,
//          but if it is, the answer is a miss.
//   range  the open interval (range.min, range.max) of acceptable t.
//
// Returns
//   the smallest t with  range.min < t < range.max  at which r(t) lies on the
//   unit sphere centred at the origin, or std::nullopt when there is none
//   (the ray misses, or every crossing lies outside the range).
//
//   * Two crossings t0 < t1: return t0 when it is inside the range, otherwise
//     t1 when that is inside the range (e.g. the ray starts inside the sphere).
//   * A tangent ray touches once (t0 == t1): return it if it is in range.
//   * Never return NaN or infinity.
//
// T is float or double: the same code is compiled for both.
template <class T>
std::optional<T> intersect_unit_sphere(const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch01
