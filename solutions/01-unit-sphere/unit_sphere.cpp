// unit_sphere.cpp — reference solution for chapter 01.
#include "01-unit-sphere/unit_sphere.hpp"

#include <cmath>

namespace rt::ch01 {

template <class T>
std::optional<T> intersect_unit_sphere(const ray<T>& r, const interval<T>& range) {
    // |o + t d|^2 = 1  expands to  (d.d) t^2 + 2 (o.d) t + (o.o - 1) = 0.
    // With half_b = o.d the factors of 2 cancel out of the quadratic formula:
    //     t = (-half_b -+ sqrt(half_b^2 - a c)) / a.
    const T a = dot(r.direction, r.direction);
    const T half_b = dot(r.origin, r.direction);
    const T c = dot(r.origin, r.origin) - T(1);

    // A zero direction is no ray at all. Written as !(a > 0) so NaN is a miss too.
    if (!(a > T(0))) return std::nullopt;

    const T discriminant = half_b * half_b - a * c;
    if (!(discriminant >= T(0))) return std::nullopt;  // no real root: the ray misses (or NaN)

    const T root = std::sqrt(discriminant);
    const T near_t = (-half_b - root) / a;  // a > 0, so this is the smaller root
    if (range.surrounds(near_t)) return near_t;
    const T far_t = (-half_b + root) / a;   // e.g. the origin is inside the sphere
    if (range.surrounds(far_t)) return far_t;
    return std::nullopt;
}

template std::optional<float> intersect_unit_sphere(const ray<float>&, const interval<float>&);
template std::optional<double> intersect_unit_sphere(const ray<double>&, const interval<double>&);

}  // namespace rt::ch01
