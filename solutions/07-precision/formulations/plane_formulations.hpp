// plane_formulations.hpp — two ways to meet a plane, and where the point lands.
//
// The plane holds every p with (p - q).n = 0. Substituting the ray gives
//     t = (q - o).n / (d.n).
// The parameter t is as good as its two dot products; the hit point
// o + t d, though, is rounded once more, and for a far or grazing hit that
// rounding can leave the point a visible distance off the plane (the start
// of "shadow acne"). Both routines return t and the point.
//
// A ray parallel to the plane (d.n = 0) or lying in it divides by zero:
// the quotient is infinite or NaN, and the range test rejects both.
#pragma once

#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <optional>

namespace rt::formulations {

template <class T>
struct plane_hit {
    T t;
    vec3<T> point;
};

// 1. The direct formula; the point is o + t d.
template <class T>
std::optional<plane_hit<T>> plane_direct(const ray<T>& ray_, const plane<T>& p, const interval<T>& range) {
    T t = dot(p.point - ray_.origin, p.normal) / dot(ray_.direction, p.normal);
    if (!range.contains(t)) return std::nullopt;
    return plane_hit<T>{t, ray_.at(t)};
}

// 2. The same t, and the point projected back onto the plane: subtract the
// point's signed distance along the normal. What remains off the plane is
// the rounding of the point's own coordinates, the least any stored point
// can have.
template <class T>
std::optional<plane_hit<T>> plane_snapped(const ray<T>& ray_, const plane<T>& p, const interval<T>& range) {
    T t = dot(p.point - ray_.origin, p.normal) / dot(ray_.direction, p.normal);
    if (!range.contains(t)) return std::nullopt;
    vec3<T> x = ray_.at(t);
    T off = dot(x - p.point, p.normal) / dot(p.normal, p.normal);
    return plane_hit<T>{t, x - off * p.normal};
}

}  // namespace rt::formulations
