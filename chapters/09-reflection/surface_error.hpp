// surface_error.hpp — a hit point, put back on its surface, and a bound on
// how far from the surface the computed point can still be.
//
// Given code (no exercise here): the spawn exercise (spawn.hpp) needs to
// know how wrong a hit point may be, and this file says, shape by shape.
// The idea is pbrt-v4's (Pharr, Jakob and Humphreys, "Physically Based
// Rendering", 4th ed., section 6.8), written out for the course's shapes.
//
// Why not just bound the error of ray.at(t)? Because t itself is rounded:
// a hit 1000 units away has t wrong by about 1000 ulp(1) * |d|, and the
// point slides that far along the ray, off the surface. So the point is first
// *reprojected*: moved onto the surface by a short computation whose rounding
// is small and known, and only the error of that computation is bounded.
//
// Every bound below is a bound per component: |computed_i - exact_i| <=
// error_i, where "exact" is the nearest point of the shape as stored in T
// (the T centre and radius, the T corners). The derivations count roundings
// with gamma(n) (README, "How far off is a hit point?"); tests check each
// bound against the exact distance on stiff cases.
#pragma once

#include "common/math.hpp"
#include "common/shapes.hpp"

#include <cmath>
#include <limits>

namespace rt::ch09 {

// gamma(n) = n u / (1 - n u), u = epsilon / 2 the unit roundoff: n roundings
// in a row change a value by a factor within (1 +- gamma(n)) (Higham,
// "Accuracy and Stability of Numerical Algorithms", lemma 3.1).
template <class T>
constexpr T gamma(int n) {
    const T u = std::numeric_limits<T>::epsilon() / T(2);
    return T(n) * u / (T(1) - T(n) * u);
}

// A point on a surface and a bound on its rounding error, per component.
template <class T>
struct surface_point {
    vec3<T> point{};
    vec3<T> error{};  // >= 0: the exact surface point is within point +- error, component by component
};

namespace detail {
template <class T>
vec3<T> abs(const vec3<T>& v) {
    return vec3<T>(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z));
}
}  // namespace detail

// The point of sphere s nearest p: c + r (p - c) / |p - c|.
// With v = p - c as computed, c + r v / |v| is exactly on the sphere whatever
// rounding v carries, so only the last steps count: |v| (3 products, 2 sums,
// a square root: within gamma(3)), r / |v| and the product with v_i (two
// more), then the sum with c_i (one more, relative to the result).
template <class T>
surface_point<T> on_sphere(const sphere<T>& s, const vec3<T>& p) {
    const vec3<T> v = p - s.center;
    const vec3<T> w = (s.radius / length(v)) * v;
    surface_point<T> sp;
    sp.point = s.center + w;
    sp.error = gamma<T>(7) * detail::abs(w) + gamma<T>(2) * detail::abs(sp.point);
    return sp;
}

// The point of the plane through q with normal m (any length) nearest p:
// p - (dot(p - q, m) / dot(m, m)) m. The rounding of a = p - q and of the
// dot product is at most gamma(4) sum |a_j m_j|; the division and product
// add a few more; the final subtraction one more, relative to the result.
template <class T>
surface_point<T> on_plane_through(const vec3<T>& q, const vec3<T>& m, const vec3<T>& p) {
    const vec3<T> a = p - q;
    const T mm = dot(m, m);
    const T s = dot(a, m) / mm;
    surface_point<T> sp;
    sp.point = p - s * m;
    const T spread = dot(detail::abs(a), detail::abs(m)) / mm;  // sum |a_j m_j| / |m|^2
    sp.error = gamma<T>(12) * spread * detail::abs(m) + gamma<T>(2) * detail::abs(sp.point);
    return sp;
}

template <class T>
surface_point<T> on_plane(const plane<T>& pl, const vec3<T>& p) {
    return on_plane_through(pl.point, pl.normal, p);
}

// The point of triangle tr's plane nearest p. The plane's normal is computed,
// m = (b - a) x (c - a), and is itself a little tilted: each component is off
// by at most gamma(5) (|e1_j e2_k| + |e1_k e2_j|), so at p the computed plane
// can stand that tilt times |p - a| away from the true one. A thin, long
// triangle (small |m| for its edges) tilts most, and gets the largest bound.
template <class T>
surface_point<T> on_triangle(const triangle<T>& tr, const vec3<T>& p) {
    const vec3<T> e1 = tr.b - tr.a, e2 = tr.c - tr.a;
    const vec3<T> m = cross(e1, e2);
    surface_point<T> sp = on_plane_through(tr.a, m, p);
    const vec3<T> f1 = detail::abs(e1), f2 = detail::abs(e2);
    const vec3<T> tilt(f1.y * f2.z + f1.z * f2.y, f1.z * f2.x + f1.x * f2.z, f1.x * f2.y + f1.y * f2.x);
    const T away = gamma<T>(6) * length(tilt) / length(m) * length(p - tr.a);
    sp.error += vec3<T>(away);
    return sp;
}

}  // namespace rt::ch09
