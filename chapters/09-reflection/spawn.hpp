// spawn.hpp — chapter 09's second exercise: where a secondary ray starts.
//
// A reflected or refracted ray leaves from a hit point that is only known to
// within its rounding error (surface_error.hpp bounds it). Started *at* the
// computed point, the new ray may find its own surface again at t ~ 0: a
// reflected ray that re-hits the mirror it leaves, a refracted ray that
// "escapes" back out through the glass it entered (README, "Where a
// secondary ray starts"). Your code goes in spawn.cpp.
#pragma once

#include "surface_error.hpp"

#include "common/math.hpp"
#include "common/ray.hpp"

namespace rt::ch09 {

// offset_ray_origin — the origin of a ray leaving a surface point in
// direction w, pushed off the surface just far enough that no point the
// error bound allows is on the ray's side of it.
//
// Inputs   p  the surface point and its error bound (surface_error.hpp)
//          n  the surface's unit normal at p (either side; its sign does not matter)
//          w  the new ray's direction (any length > 0)
// Returns  o = p.point + s * n, where
//              s = +dot(|n|, p.error)  if dot(w, n) >= 0   (the ray leaves on n's side)
//              s = -dot(|n|, p.error)  if dot(w, n) <  0   (it leaves on the other side)
//          |n| = (|n.x|, |n.y|, |n.z|): the error box projected on the normal,
//          how far along n the exact surface can be from the computed point.
//          Then each component of o that moved is stepped one float further
//          in the direction it moved (std::nextafter): the sum p + s n is
//          itself rounded, possibly back towards the surface.
//   * Along the normal only, never along w: sliding along w does not leave a
//     surface that w grazes.
//   * The offset is at most dot(|n|, error) plus one float step per
//     component, so a surface farther than that from p along the normal (a
//     glass pane, a bubble's far wall) is never skipped by the new ray.
//   * A zero error bound (an exact point) leaves p.point as it is.
template <class T>
vec3<T> offset_ray_origin(const surface_point<T>& p, const vec3<T>& n, const vec3<T>& w);

// The ray leaving p in direction w, started at offset_ray_origin (given code).
// Its hits count for t > 0 (interval (0, infinity)).
template <class T>
ray<T> spawn_ray(const surface_point<T>& p, const vec3<T>& n, const vec3<T>& w) {
    return ray<T>{offset_ray_origin(p, n, w), w};
}

}  // namespace rt::ch09
