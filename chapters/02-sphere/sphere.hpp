// sphere.hpp — chapter 02's exercise: a ray against a sphere anywhere, of any size.
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
//     normal  the outward unit normal (point - s.center) / s.radius
//     object  left at -1 (the scene loop of chapter 03 fills it in)
//   Never a NaN or infinite t.
template <class T>
std::optional<hit_record<T>> intersect_sphere(const sphere<T>& s, const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch02
