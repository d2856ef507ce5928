// reference.hpp — the right answers, computed with MPFR from the same inputs.
//
// A formulation's error is measured against the answer that exact
// arithmetic gives for the very same float or double inputs it was handed.
// So the inputs are taken exactly (every float and double is a rational
// number), every sum and product is carried with enough bits to be exact
// (the precision is chosen from the spread of the inputs' exponents), and
// only the final square root and divisions round, at hundreds of bits. The
// roots use the stable pair (c/q, q/a), so the reference itself does not
// cancel. Whatever error remains is the formulation's, not the input's.
#pragma once

#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

namespace rt::study {

struct reference_answer {
    bool hit = false;        // a crossing inside (range.min, range.max)
    long double t = 0;       // that crossing (nearest one in range)
    double t_rounded = 0;    // t correctly rounded to the input's precision
    bool has_roots = false;  // sphere: the line meets the sphere at all
    long double t_near = 0, t_far = 0;  // sphere: both crossings of the line
};

// Sphere: invalid input (NaN, infinity, zero direction, radius <= 0) is a miss.
template <class T>
reference_answer sphere_reference(const ray<T>& r, const sphere<T>& s, const interval<T>& range);

// Plane: parallel or lying in the plane (d.n = 0) is a miss.
template <class T>
reference_answer plane_reference(const ray<T>& r, const plane<T>& p, const interval<T>& range);

// Triangle: edges and corners count as inside; a degenerate triangle or a
// ray parallel to its plane is a miss.
template <class T>
reference_answer triangle_reference(const ray<T>& r, const triangle<T>& tri, const interval<T>& range);

// How far the point x lies off the plane, in ULPs of the largest coordinate
// of x and of the plane's point (a stored point can be off by up to about
// 0.9 of those: each coordinate is rounded by half an ULP).
template <class T>
double off_plane_ulps(const plane<T>& p, const vec3<T>& x);

}  // namespace rt::study
