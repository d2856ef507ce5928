// scene_loop.hpp — chapter 03's exercise: the closest hit among many objects.
//
// This header is the contract; your code goes in scene_loop.cpp, and the
// reference solution implements exactly the same declaration.
#pragma once

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"

#include <functional>
#include <optional>

namespace rt::ch03 {

// How the loop asks "does the ray hit object i inside this range?".
// The caller decides what object i is (a sphere, a plane, a triangle...).
template <class T>
using object_intersector = std::function<std::optional<hit_record<T>>(int i, const ray<T>& r, const interval<T>& range)>;

// closest_hit
//
// Inputs
//   object_count  the objects are numbered 0 .. object_count-1
//   intersect     intersect(i, r, range) tests object i (see above)
//   r             the ray
//   range         the open interval (range.min, range.max) of acceptable t
//
// Returns
//   the hit with the smallest t over all objects, with its `object` field
//   set to the index of the object hit, or std::nullopt when no object is hit
//   inside the range. The answer does not depend on the order of the objects.
//   Each object is tested once, in the order 0, 1, ..., with the caller's
//   range.min and with range.max shrunk to the closest t found so far.
//
//   * No objects (object_count <= 0): a miss, and intersect is never called.
//   * Two objects hit at exactly the same t: the one tested first is kept
//     (the range is open, so the second is not hit inside (min, t)).
//   * The hit record is the one object's intersect returned, unchanged
//     except for its `object` field.
//
// T is float or double: the same code is compiled for both.
template <class T>
std::optional<hit_record<T>> closest_hit(int object_count, const object_intersector<T>& intersect, const ray<T>& r,
                                         interval<T> range);

}  // namespace rt::ch03
