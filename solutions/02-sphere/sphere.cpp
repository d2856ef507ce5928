// sphere.cpp — reference solution for chapter 02.
#include "02-sphere/sphere.hpp"

#include <cmath>

namespace rt::ch02 {

template <class T>
std::optional<hit_record<T>> intersect_sphere(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    // |o + t d - C|^2 = R^2. With oc = o - C this expands to
    //     (d.d) t^2 + 2 (oc.d) t + (oc.oc - R^2) = 0,
    // and with half_b = oc.d the factors of 2 cancel out of the quadratic formula:
    //     t = (-half_b -+ sqrt(half_b^2 - a c)) / a.
    // Moving the origin to the centre first (oc) keeps the numbers small for
    // a sphere far from the world origin.
    const vec3<T> oc = r.origin - s.center;
    const T a = dot(r.direction, r.direction);
    const T half_b = dot(oc, r.direction);
    const T c = dot(oc, oc) - s.radius * s.radius;

    // A zero direction is no ray at all. Written as !(a > 0) so NaN is a miss too.
    if (!(a > T(0))) return std::nullopt;

    const T discriminant = half_b * half_b - a * c;
    if (!(discriminant >= T(0))) return std::nullopt;  // no real root: the ray misses (or NaN)

    // Nearest root first; a > 0, so the minus sign gives the smaller t.
    const T root = std::sqrt(discriminant);
    T t = (-half_b - root) / a;
    if (!range.surrounds(t)) {
        t = (-half_b + root) / a;  // e.g. the origin is inside the sphere
        if (!range.surrounds(t)) return std::nullopt;
    }

    hit_record<T> hit;
    hit.t = t;
    hit.point = r.at(t);
    // Every surface point is exactly R from the centre, so dividing by R
    // (rather than normalising) gives the unit normal, pointing outwards.
    hit.normal = (hit.point - s.center) / s.radius;
    return hit;
}

template std::optional<hit_record<float>> intersect_sphere(const sphere<float>&, const ray<float>&,
                                                           const interval<float>&);
template std::optional<hit_record<double>> intersect_sphere(const sphere<double>&, const ray<double>&,
                                                            const interval<double>&);

}  // namespace rt::ch02
