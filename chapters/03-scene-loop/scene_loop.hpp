// scene_loop.hpp — chapter 03's exercise: the closest hit among many objects.
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
//   Each object is tested once, with the upper end of the range shrunk to the
//   closest t found so far.
template <class T>
std::optional<hit_record<T>> closest_hit(int object_count, const object_intersector<T>& intersect, const ray<T>& r,
                                         interval<T> range);

}  // namespace rt::ch03
