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
//   p      a plane through p.point with normal p.normal (not necessarily unit, never zero)
//   r      a ray r(t) = r.origin + t * r.direction
//   range  the open interval (range.min, range.max) of acceptable t
//
// Returns
//   the hit if its t lies in (range.min, range.max), else std::nullopt:
//     t       ray parameter of the crossing
//     point   r.at(t)
//     normal  the plane's unit normal, turned to face the ray's origin
//             (dot(normal, r.direction) < 0), so a plane hit from behind
//             is shaded like one hit from the front
//     object  left at -1
//   A ray parallel to the plane (including one lying in it) is a miss: never
//   a NaN, never an infinity, never a division by zero that passes as a hit.
template <class T>
std::optional<hit_record<T>> intersect_plane(const plane<T>& p, const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch04
