// triangle_formulations.hpp — three ray-triangle tests and the cracks between triangles.
//
// A closed mesh has no holes, but a ray aimed exactly at an edge shared by
// two triangles is decided twice, once per triangle, each time with its own
// rounding. If both triangles round the ray to their outside, the ray
// passes through the surface: a "leak", a dark or bright pixel on the
// silhouette of every edge. Edges count as inside here (>= 0 tests), which
// is what a closed mesh needs.
//
// Every routine: the t with range.min < t < range.max where the ray meets
// the triangle, or std::nullopt. A degenerate triangle, a ray parallel to
// the triangle or lying in its plane, is a miss, decided EXACTLY
// (exact_sign.hpp's flat_exactly, asked only about rays that would
// otherwise hit): rounding can make the determinant of such a ray a tiny
// non-zero number. A non-zero direction too small for its products to stay
// normal (subnormal) is scaled by a power of two first (t scales back).
// The triangle itself is not rescaled: one whose edge products underflow
// (edges below about 1e-19 in float, 1e-154 in double) has a rounded
// determinant of 0 and is missed; chapter 05's solution shows the
// rescaling such triangles need.
#pragma once

#include "exact_sign.hpp"

#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/shapes.hpp"

#include <cmath>
#include <optional>
#include <utility>

namespace rt::formulations {

namespace detail {
// o + t d = o + t' (2^k d): run F on the scaled direction with an unbounded
// range, then scale t' back and apply the caller's range.
template <auto F, class T>
std::optional<T> with_scaled_direction(const ray<T>& ray_, const triangle<T>& tri, const interval<T>& range, int k) {
    const vec3<T>& d = ray_.direction;
    ray<T> scaled{ray_.origin, vec3<T>(std::ldexp(d.x, k), std::ldexp(d.y, k), std::ldexp(d.z, k))};
    std::optional<T> t = F(scaled, tri, interval<T>{-infinity<T>, infinity<T>});
    if (!t) return std::nullopt;
    T back = std::ldexp(*t, k);
    if (!range.surrounds(back)) return std::nullopt;
    return back;
}
}  // namespace detail

// 1. The lecture's method: meet the triangle's plane, then ask whether the
// hit point lies on the inner side of each edge (three half-planes). The
// point is rounded before the edge tests, so neighbouring triangles judge
// slightly different points: leaks happen.
template <class T>
std::optional<T> triangle_half_planes(const ray<T>& ray_, const triangle<T>& tri, const interval<T>& range) {
    if (const int k = direction_scale(ray_.direction); k != 0)
        return detail::with_scaled_direction<&triangle_half_planes<T>>(ray_, tri, range, k);
    vec3<T> n = cross(tri.b - tri.a, tri.c - tri.a);
    T t = dot(tri.a - ray_.origin, n) / dot(ray_.direction, n);
    if (!range.surrounds(t)) return std::nullopt;
    vec3<T> p = ray_.at(t);
    bool inside = dot(cross(tri.b - tri.a, p - tri.a), n) >= 0 && dot(cross(tri.c - tri.b, p - tri.b), n) >= 0 &&
                  dot(cross(tri.a - tri.c, p - tri.c), n) >= 0;
    if (!inside || flat_exactly(ray_.direction, tri.a, tri.b, tri.c)) return std::nullopt;
    return t;
}

// 2. Moeller and Trumbore (1997): solve o + t d = a + u e1 + v e2 by
// Cramer's rule with shared cross products; no plane equation is stored.
// Fast, but the barycentrics u and v of two neighbouring triangles are
// rounded independently, so u + v <= 1 on one side and u >= 0 on the other
// can both fail for a ray through the shared edge. No epsilon here: we
// measure the formula itself.
template <class T>
std::optional<T> triangle_moller_trumbore(const ray<T>& ray_, const triangle<T>& tri, const interval<T>& range) {
    if (const int k = direction_scale(ray_.direction); k != 0)
        return detail::with_scaled_direction<&triangle_moller_trumbore<T>>(ray_, tri, range, k);
    vec3<T> e1 = tri.b - tri.a, e2 = tri.c - tri.a;
    vec3<T> pv = cross(ray_.direction, e2);
    T det = dot(e1, pv);
    if (det == 0) return std::nullopt;
    T inv = T(1) / det;
    vec3<T> tv = ray_.origin - tri.a;
    T u = dot(tv, pv) * inv;
    if (!(u >= 0 && u <= 1)) return std::nullopt;
    vec3<T> qv = cross(tv, e1);
    T v = dot(ray_.direction, qv) * inv;
    if (!(v >= 0 && u + v <= 1)) return std::nullopt;
    T t = dot(e2, qv) * inv;
    if (!range.surrounds(t) || flat_exactly(ray_.direction, tri.a, tri.b, tri.c)) return std::nullopt;
    return t;
}

namespace detail {
template <class T>
T component(const vec3<T>& v, int k) {
    return k == 0 ? v.x : (k == 1 ? v.y : v.z);
}

// The wider type used when an edge function comes out exactly zero.
template <class T>
using wider = std::conditional_t<sizeof(T) == sizeof(float), double, long double>;

// 2D edge function x1 y2 - y1 x2, recomputed in wider precision when it is
// exactly zero in T (then its sign is the only thing that matters).
template <class T>
T edge_function(T x1, T y1, T x2, T y2) {
    T e = x1 * y2 - y1 * x2;
    if (e == 0) {
        using W = wider<T>;
        e = static_cast<T>(W(x1) * W(y2) - W(y1) * W(x2));
    }
    return e;
}
}  // namespace detail

// 3. The watertight test of Woop, Benthin and Wald (JCGT 2013). Move the
// ray origin to 0, permute axes so the direction's largest component is z,
// and shear so the ray becomes the z axis. The test is then 2D: the signs of
// three edge functions of the sheared vertices. Neighbouring triangles
// share the very same sheared vertices (the transform depends only on the
// ray), so they evaluate the same edge function with the same roundings
// and cannot both say "outside" (the edge function of a shared edge is
// computed from the same two numbers, with opposite signs).
template <class T>
std::optional<T> triangle_watertight(const ray<T>& ray_, const triangle<T>& tri, const interval<T>& range) {
    if (const int k = direction_scale(ray_.direction); k != 0)
        return detail::with_scaled_direction<&triangle_watertight<T>>(ray_, tri, range, k);
    const vec3<T>& d = ray_.direction;
    vec3<T> ad(std::fabs(d.x), std::fabs(d.y), std::fabs(d.z));
    int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (detail::component(d, kz) < 0) std::swap(kx, ky);  // keep the winding
    T dz = detail::component(d, kz);
    T sx = detail::component(d, kx) / dz, sy = detail::component(d, ky) / dz, sz = T(1) / dz;

    vec3<T> A = tri.a - ray_.origin, B = tri.b - ray_.origin, C = tri.c - ray_.origin;
    using detail::component;
    T ax = component(A, kx) - sx * component(A, kz), ay = component(A, ky) - sy * component(A, kz);
    T bx = component(B, kx) - sx * component(B, kz), by = component(B, ky) - sy * component(B, kz);
    T cx = component(C, kx) - sx * component(C, kz), cy = component(C, ky) - sy * component(C, kz);

    T u = detail::edge_function(cx, cy, bx, by);
    T v = detail::edge_function(ax, ay, cx, cy);
    T w = detail::edge_function(bx, by, ax, ay);
    bool some_negative = u < 0 || v < 0 || w < 0, some_positive = u > 0 || v > 0 || w > 0;
    if (some_negative && some_positive) return std::nullopt;
    T det = u + v + w;
    if (det == 0) return std::nullopt;  // the ray lies in the triangle's plane
    T num = u * (sz * component(A, kz)) + v * (sz * component(B, kz)) + w * (sz * component(C, kz));
    T t = num / det;
    if (!range.surrounds(t) || flat_exactly(d, tri.a, tri.b, tri.c)) return std::nullopt;
    return t;
}

}  // namespace rt::formulations
