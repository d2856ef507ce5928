// plane_formulations.hpp — two ways to meet a plane, and where the point lands.
//
// The plane holds every p with (p - q).n = 0. Substituting the ray gives
//     t = (q - o).n / (d.n).
// The parameter t is as good as its two dot products; the hit point
// o + t d, though, is rounded once more, and for a far or grazing hit that
// rounding can leave the point a visible distance off the plane (the start
// of "shadow acne"). Both routines return t and the point.
//
// A ray parallel to the plane or lying in it is a miss, decided on the
// EXACT d.n (exact_sign.hpp): a rounded d.n can be a tiny non-zero number
// for an exactly parallel ray, and dividing by it would give a false hit at
// an enormous t. A direction so small that d.n would underflow (a
// subnormal, but non-zero, direction) is first scaled by a power of two;
// t scales back exactly. So is a normal of any finite length (its length
// cancels from t).
#pragma once

#include "exact_sign.hpp"

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

namespace detail {
template <class T>
vec3<T> times_power_of_two(const vec3<T>& v, int k) {
    return k == 0 ? v : vec3<T>(std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k));
}

// The normal times a power of two that keeps its products with points and
// directions finite and normal (a normal of length 1e30 or 1e-30 in float):
// the length of n cancels from t, so only its direction matters.
template <class T>
vec3<T> comfortable_normal(const plane<T>& p) {
    return times_power_of_two(p.normal, direction_scale(p.normal));
}

// t = (q - o).n / d.n, or NaN when d.n is exactly 0 (parallel or in the
// plane; NaN fails every range test).
template <class T>
T plane_t(const ray<T>& ray_, const plane<T>& p) {
    if (parallel_exactly(ray_.direction, p.normal)) return std::numeric_limits<T>::quiet_NaN();
    const vec3<T> n = comfortable_normal(p);
    const int k = direction_scale(ray_.direction);
    if (k == 0) return dot(p.point - ray_.origin, n) / dot(ray_.direction, n);
    // o + t' (2^k d) is the same point as o + t d when t = 2^k t'.
    return std::ldexp(dot(p.point - ray_.origin, n) / dot(times_power_of_two(ray_.direction, k), n), k);
}
}  // namespace detail

// 1. The direct formula; the point is o + t d.
template <class T>
std::optional<plane_hit<T>> plane_direct(const ray<T>& ray_, const plane<T>& p, const interval<T>& range) {
    T t = detail::plane_t(ray_, p);
    if (!range.surrounds(t)) return std::nullopt;
    return plane_hit<T>{t, ray_.at(t)};
}

// 2. The same t, and the point projected back onto the plane: subtract the
// point's signed distance along the normal. What remains off the plane is
// the rounding of the point's own coordinates, the least any stored point
// can have.
//
// A hit is reported with a finite point or not at all. A ray nearly parallel
// to the plane can meet it at a t near T's largest numbers (a float ray at
// t near 2^127), where o + t d lies beyond T's range: no point of T holds it,
// so the hit is not reported. Where o + t d is finite but its products with
// the normal overflow (components near T's largest), the distance is taken
// on the difference scaled by a power of two, which changes no digit.
template <class T>
std::optional<plane_hit<T>> plane_snapped(const ray<T>& ray_, const plane<T>& p, const interval<T>& range) {
    T t = detail::plane_t(ray_, p);
    if (!range.surrounds(t)) return std::nullopt;
    vec3<T> x = ray_.at(t);
    if (!is_finite(x)) return std::nullopt;
    const vec3<T> n = detail::comfortable_normal(p);
    const vec3<T> e = x - p.point;
    T off = dot(e, n) / dot(n, n);
    if (!std::isfinite(off) && is_finite(e)) {
        const int k = direction_scale(e);  // 2^k e has its largest component near 1
        off = std::ldexp(dot(detail::times_power_of_two(e, k), n) / dot(n, n), -k);
    }
    const vec3<T> snapped = x - off * n;
    if (!is_finite(snapped)) return std::nullopt;
    return plane_hit<T>{t, snapped};
}

}  // namespace rt::formulations
