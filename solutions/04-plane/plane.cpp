// plane.cpp — reference solution for chapter 04.
#include "04-plane/plane.hpp"

#include <algorithm>
#include <cmath>

namespace rt::ch04 {

namespace {

// The plane's normal at unit length. Dividing by the largest component first
// keeps length() from overflowing (normal ~ 1e30 in float) or underflowing
// (normal ~ 1e-30) on the way: the direction is all that matters.
template <class T>
vec3<T> unit_normal(const vec3<T>& n) {
    const T largest = std::max({std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)});
    const vec3<T> scaled = n / largest;
    return scaled / length(scaled);
}

// The power of two that brings the direction's largest component to about
// 1, or 0 when it is already in a range where its products with the unit
// normal stay normal numbers (every ordinary ray: nothing to do).
template <class T>
int direction_exponent(const vec3<T>& d) {
    const T largest = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
    if (largest >= T(0x1p-30) || !(largest > T(0))) return 0;
    return -std::ilogb(largest);
}

}  // namespace

template <class T>
std::optional<hit_record<T>> intersect_plane(const plane<T>& p, const ray<T>& r, const interval<T>& range) {
    // (o + t d - p0) . n = 0  gives  t = (p0 - o) . n / (d . n).
    // Using the unit normal does not change t (the length of n cancels) but
    // gives us the normal the hit record needs.
    const vec3<T> n = unit_normal(p.normal);
    // A direction with tiny (even subnormal) components is still a direction,
    // but d . n would lose its digits or underflow to 0. Scaling it by a
    // power of two (exact) keeps them: o + t' (2^k d) is o + t d for
    // t = 2^k t', so t scales back exactly below.
    const int k = direction_exponent(r.direction);
    const vec3<T> d = k == 0 ? r.direction
                             : vec3<T>(std::ldexp(r.direction.x, k), std::ldexp(r.direction.y, k),
                                       std::ldexp(r.direction.z, k));
    const T facing = dot(d, n);

    // d . n == 0: the ray runs parallel to the plane (above it, or inside
    // it). There is no single crossing, so it is a miss; dividing anyway
    // would give +-infinity or 0/0 = NaN. Written as !(|d.n| > 0) so a NaN
    // (zero normal, NaN input) is a miss as well.
    if (!(std::fabs(facing) > T(0))) return std::nullopt;

    const T t = k == 0 ? dot(p.point - r.origin, n) / facing : std::ldexp(dot(p.point - r.origin, n) / facing, k);
    // A tiny d.n can still push t to infinity: surrounds() rejects infinity
    // and NaN, but say so explicitly for the reader.
    if (!std::isfinite(t) || !range.surrounds(t)) return std::nullopt;

    hit_record<T> hit;
    hit.t = t;
    hit.point = r.at(t);
    // The plane's own normal, from whichever side the ray comes: which side
    // that is, is hit.front_face(r) (common/hit_record.hpp), decided once for
    // every shape.
    hit.normal = n;
    return hit;
}

template std::optional<hit_record<float>> intersect_plane(const plane<float>&, const ray<float>&, const interval<float>&);
template std::optional<hit_record<double>> intersect_plane(const plane<double>&, const ray<double>&,
                                                           const interval<double>&);

}  // namespace rt::ch04
