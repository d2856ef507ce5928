// aabb.hpp — axis-aligned bounding boxes, and chapter 08's first exercise:
// the robust slab test.
//
// A box is the set of points p with lo <= p <= hi in every coordinate
// (closed: its faces belong to it). The given part of this file makes boxes
// (empty, around points, around spheres and triangles, around other boxes)
// and measures them; the exercise, intersect_box, is the contract at the end.
// Your code goes in slab_test.cpp; the reference solution implements exactly
// the same declaration. README.md, "The slab test", is the lecture.
#pragma once

#include "common/interval.hpp"
#include "common/math.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace rt::ch08 {

template <class T>
struct aabb {
    // The empty box: lo > hi in every coordinate, so growing it by anything
    // gives exactly that thing's box.
    vec3<T> lo{infinity<T>, infinity<T>, infinity<T>};
    vec3<T> hi{-infinity<T>, -infinity<T>, -infinity<T>};

    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }

    void grow(const vec3<T>& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }

    vec3<T> centroid() const { return (lo + hi) * T(0.5); }

    // Half the surface area, (dx dy + dy dz + dz dx): the surface area
    // heuristic only ever compares ratios of areas, so the factor 2 is left
    // out. 0 for an empty box, a point or a line; positive for a flat box.
    T half_area() const {
        if (empty()) return T(0);
        const vec3<T> e = hi - lo;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }

    // True when b lies inside this box (faces may touch).
    bool contains(const aabb& b) const {
        return lo.x <= b.lo.x && lo.y <= b.lo.y && lo.z <= b.lo.z && b.hi.x <= hi.x && b.hi.y <= hi.y &&
               b.hi.z <= hi.z;
    }
};

// The box of a triangle: its corners' smallest and largest coordinates,
// exact (no arithmetic, only comparisons).
template <class T>
aabb<T> bounds(const triangle<T>& t) {
    aabb<T> b;
    b.grow(t.a);
    b.grow(t.b);
    b.grow(t.c);
    return b;
}

// The box of a sphere: center -/+ radius, padded outwards. A box must hold
// every point where the sphere test can REPORT a hit, not only the exact
// sphere: center + radius is rounded (possibly inwards), and near the
// silhouette the sphere test's answer is ill-conditioned (chapter 07), so a
// grazing ray can be reported as a hit a little outside the exact sphere. A
// box that cut such a hit off would make the tree miss what brute force
// finds. The pad, sqrt(epsilon) of the sphere's largest coordinate (about
// 3e-4 in float), covers that error for rays from up to about 1/sqrt(epsilon)
// radii away, and costs nothing measurable (README, "Boxes must really bound").
template <class T>
aabb<T> bounds(const sphere<T>& s) {
    const T r = std::fabs(s.radius);
    const vec3<T> c = s.center;
    const T size = std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z), r});
    const T pad = std::sqrt(std::numeric_limits<T>::epsilon()) * size;
    const vec3<T> reach{r + pad, r + pad, r + pad};
    return {c - reach, c + reach};
}

// The reciprocal of a ray's direction, one division per component, computed
// once per ray rather than once per box. A zero component gives an infinity
// with the zero's sign: 1 / +0 = +inf, 1 / -0 = -inf (IEEE 754). The slab
// test must cope with what those infinities do (README, "Zero directions").
template <class T>
vec3<T> reciprocal(const vec3<T>& d) {
    return {T(1) / d.x, T(1) / d.y, T(1) / d.z};
}

// widen_exit — moves a slab test's exit outwards by 4 epsilons of its
// magnitude (README, "A conservative slab test"). Every slab parameter is
// (p - o) * (1/d): three roundings, so it is within a factor (1 +- gamma(3))
// of the exact value, gamma(n) = n u / (1 - n u) with u = epsilon / 2 the unit
// roundoff. An entry rounded up and an exit rounded down can cross although
// the exact ones do not; moving the exit outwards by 2 gamma(3) of its
// magnitude (6 u, plus the rounding of this very multiplication: 8 u = 4
// epsilon is enough) undoes that. Both factors are exact in T; infinities
// stay infinities. The traversal uses the same widening when it compares a
// stored entry with the closest hit so far.
template <class T>
T widen_exit(T exit) {
    constexpr T up = T(1) + T(4) * std::numeric_limits<T>::epsilon();
    constexpr T down = T(1) - T(4) * std::numeric_limits<T>::epsilon();
    return exit >= T(0) ? exit * up : exit * down;
}

// intersect_box — the slab test. Does the ray meet the box inside the range?
//
// Inputs
//   box            the box; lo <= hi in every coordinate. A flat box
//                  (lo == hi in one or two coordinates: the box of a planar
//                  mesh, or of one axis-aligned triangle) and a point box are
//                  allowed and are hit like any other box.
//   r              the ray r(t) = r.origin + t * r.direction, not necessarily
//                  unit length. Components of the direction may be +0 or -0.
//   inv_direction  reciprocal(r.direction), computed once by the caller.
//   range          the parameters the caller still cares about.
//
// Returns
//   the parameter at which the ray enters the box, clamped to the range:
//       entry = max(range.min, the largest of the three slab entries)
//   when entry <= exit, where
//       exit  = widen_exit(min(range.max, the smallest of the three slab exits)),
//   and std::nullopt otherwise (the box is missed, or it lies entirely before
//   range.min or beyond range.max).
//   The slab of axis k is lo.k <= o.k + t d.k <= hi.k; its entry and exit are
//   the smaller and larger of (lo.k - o.k) / d.k and (hi.k - o.k) / d.k.
//
// The promise (this is what the tree's exactness rests on)
//   * Conservative: if the exact ray, from the very inputs given, has a point
//     r(t) in the closed box with range.min <= t <= range.max, the answer is
//     a hit, whatever the rounding. Touching a face, an edge or a corner is a
//     hit; a ray lying in a face's plane is a hit.
//   * Comparisons are closed (<=), not the open rule of object tests: a box
//     is only a promise that something MAY be hit there.
//   * A direction component that is +0 or -0: the ray is parallel to that
//     slab. Its origin is inside the slab (lo.k <= o.k <= hi.k, the faces
//     included) or the box is missed. 0 * infinity = NaN appears when the
//     origin lies exactly on a face plane: a NaN must never make a box the
//     ray crosses look missed.
//   * A direction component that is subnormal (not zero, but so small that
//     its reciprocal overflows to infinity) is NOT parallel: the ray crosses
//     that slab at (lo.k - o.k) / d.k and (hi.k - o.k) / d.k, which may be
//     ordinary numbers. For such a component, divide by d.k instead of
//     multiplying by the infinite reciprocal.
//   * entry is never NaN. A ray starting inside the box returns range.min.
//   * Because the exit is widened, a box entered a few units in the last
//     place beyond range.max can still be reported: that is the price of
//     never missing one entered exactly at range.max.
//   * range.min may be -infinity and range.max +infinity.
//   Outside the promise: coordinates so large that (p - o) overflows, and
//   slab parameters so small that they are subnormal (a slab parameter, t,
//   not a direction component: those are covered above).
//
// T is float or double: the same code is compiled for both.
template <class T>
std::optional<T> intersect_box(const aabb<T>& box, const ray<T>& r, const vec3<T>& inv_direction,
                               const interval<T>& range);

}  // namespace rt::ch08
