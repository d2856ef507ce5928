// sphere.hpp — chapter 02's exercise: a ray against a sphere anywhere, of any size.
//
// The sphere is every point P with  (P - C) . (P - C) = R^2. This header is
// the contract; your code goes in sphere.cpp, and the reference solution
// implements exactly the same declaration.
#pragma once

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <optional>

namespace rt::ch02 {

// intersect_sphere
//
// Inputs
//   s      a sphere: centre s.center, radius s.radius > 0.
//   r      a ray r(t) = r.origin + t * r.direction; the direction need not be
//          unit length. A zero direction is a miss.
//   range  the open interval (range.min, range.max) of acceptable t.
//
// Returns
//   the hit with the smallest t in (range.min, range.max), or std::nullopt:
//     t       the ray parameter (the nearer root if it is in range, else the
//             farther root if that is in range, e.g. when the origin is inside)
//     point   r.at(t)
//     normal  the outward unit normal (point - s.center) / s.radius; outward
//             even when the ray starts inside the sphere
//     object  left at -1 (the scene loop of chapter 03 fills it in)
//
//   * The range is open: a root exactly at range.min or range.max is no hit.
//   * A tangent ray touches once (both roots equal): a hit if it is in range.
//   * A miss: the ray passes farther than R from the centre, or every
//     crossing lies outside the range (e.g. the sphere is behind the ray).
//   * Never a NaN or infinite t; a NaN anywhere in the input is a miss.
//
// T is float or double: the same code is compiled for both.
template <class T>
std::optional<hit_record<T>> intersect_sphere(const sphere<T>& s, const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch02
