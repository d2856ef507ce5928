// triangle.hpp — chapter 05's exercise: a ray against a triangle.
//
// A triangle is the part of its plane on the inner side of its three edges.
// The exercise hits the plane (chapter 04's formula) and then tests the
// point against the edges; the signed areas that test computes are the
// point's barycentric coordinates. This header is the contract; your code
// goes in triangle.cpp, and the reference solution implements the same
// declarations.
#pragma once

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <optional>

namespace rt::ch05 {

// barycentric
//
// Inputs   tri, and a point p assumed to lie in the triangle's plane.
// Returns  (alpha, beta, gamma) with p = alpha*a + beta*b + gamma*c and
//          alpha + beta + gamma = 1. All three are >= 0 exactly when p is
//          inside the triangle or on its edges; outside, the coordinate of
//          the corner opposite a crossed edge is negative (signed areas).
//          alpha belongs to corner a, beta to b, gamma to c.
//          A degenerate triangle (zero area) returns NaN in all three.
template <class T>
vec3<T> barycentric(const triangle<T>& tri, const vec3<T>& p);

// intersect_triangle — the lecture's method: hit the triangle's plane, then
// test the hit point against the three edge half-planes.
//
// Inputs
//   tri    the triangle (corners a, b, c)
//   r      a ray r(t) = r.origin + t * r.direction
//   range  the open interval (range.min, range.max) of acceptable t
//
// Returns
//   the hit if the ray crosses the triangle (edges and corners count as
//   inside) at a t in (range.min, range.max), else std::nullopt:
//     t       ray parameter
//     point   r.at(t)
//     normal  the outward unit normal (b - a) x (c - a) / |(b - a) x (c - a)|:
//             the side from which a -> b -> c runs counter-clockwise, from
//             either side (a ray from behind gets the same normal, and
//             hit.front_face(r) is false: common/hit_record.hpp's one rule)
//     object  left at -1
//   A degenerate triangle (zero area) and a ray parallel to the triangle's
//   plane are misses, never NaN. "Zero" is as computed in T: when rounding
//   makes the n of an exactly degenerate triangle, or the d.n of a ray lying
//   exactly in the plane, a tiny non-zero number, a hit may be reported; it
//   is then a point of the ray (deciding exactly is chapter 07's subject).
//
// Both functions: a triangle of any size, even one whose edge^4 overflows or
// underflows T (edges of 1e10 or 1e-12 in float, 1e80 or 1e-80 in double),
// gives the same answers as the same triangle at unit size: scale the edges
// by a power of two before multiplying them (README, "Very small and very
// large triangles"). A direction with tiny, even subnormal, components is
// not zero: scale it the same way before taking d.n (t scales back
// exactly). The tests ask it: a triangle of subnormal size hit by a ray whose
// direction is as small must give the same t as at unit size.
template <class T>
std::optional<hit_record<T>> intersect_triangle(const triangle<T>& tri, const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch05
