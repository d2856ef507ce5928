// triangle.cpp — reference solution for chapter 05.
#include "05-triangle/triangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rt::ch05 {

namespace {

// Barycentric coordinates and the direction of the normal do not change
// when the whole triangle is scaled. Bringing the edge vectors to about unit
// size keeps the cross products below from overflowing (edges ~ 1e20 in
// float) or vanishing into zero (edges ~ 1e-20). The factor is a power of
// two, so the scaling itself is exact and adds no rounding error.
template <class T>
int size_exponent(const vec3<T>& u, const vec3<T>& v) {
    const T largest =
        std::max({std::fabs(u.x), std::fabs(u.y), std::fabs(u.z), std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    // Edges between 2^-30 and 2^30 need no rescaling (n . n ~ edge^4 fits even
    // in a float), and that is every ordinary scene: skip the work there.
    if (largest >= T(0x1p-30) && largest <= T(0x1p30)) return 0;
    if (!(largest > T(0)) || !std::isfinite(largest)) return 0;  // degenerate or not finite: nothing to rescale
    return std::ilogb(largest);
}

// v * 2^-exponent, as two exact multiplications: one factor 2^-exponent
// would overflow a float when the edges are subnormal (exponent < -127).
template <class T>
vec3<T> scaled_down(const vec3<T>& v, int exponent) {
    if (exponent == 0) return v;
    const int first = -exponent / 2;
    return v * std::ldexp(T(1), first) * std::ldexp(T(1), -exponent - first);
}

}  // namespace

template <class T>
vec3<T> barycentric(const triangle<T>& tri, const vec3<T>& p) {
    // Work relative to corner a, in units of the largest edge component.
    const int e = size_exponent(tri.b - tri.a, tri.c - tri.a);
    const vec3<T> ab = scaled_down(tri.b - tri.a, e);
    const vec3<T> ac = scaled_down(tri.c - tri.a, e);
    const vec3<T> ap = scaled_down(p - tri.a, e);
    const vec3<T> bc = ac - ab;  // c - b
    const vec3<T> bp = ap - ab;  // p - b

    // n = (b - a) x (c - a) is twice the area times the unit normal.
    const vec3<T> n = cross(ab, ac);
    const T twice_area_squared = dot(n, n);
    if (!(twice_area_squared > T(0))) {  // zero area (or NaN corners): no coordinates exist
        const T nan = std::numeric_limits<T>::quiet_NaN();
        return {nan, nan, nan};
    }

    // Each coordinate is the signed area of the sub-triangle opposite its
    // corner, divided by the whole area. The sign comes from the edge
    // half-plane test: (edge x (p - edge start)) . n >= 0 when p is on the
    // inner side of that edge.
    const T alpha = dot(cross(bc, bp), n) / twice_area_squared;  // edge b -> c, opposite a
    const T beta = dot(cross(ap, ac), n) / twice_area_squared;   // edge c -> a, opposite b
    const T gamma = dot(cross(ab, ap), n) / twice_area_squared;  // edge a -> b, opposite c
    return {alpha, beta, gamma};
}

template <class T>
std::optional<hit_record<T>> intersect_triangle(const triangle<T>& tri, const ray<T>& r, const interval<T>& range) {
    // Step 1: the triangle's plane, through a with normal n = (b - a) x (c - a).
    const int e = size_exponent(tri.b - tri.a, tri.c - tri.a);
    const vec3<T> n = cross(scaled_down(tri.b - tri.a, e), scaled_down(tri.c - tri.a, e));
    // A direction with tiny (even subnormal) components: scaled the same way
    // (by a power of two, exact), so d . n keeps its digits; o + t' (2^-k d)
    // is o + t d for t = 2^-k t'.
    const int k = size_exponent(r.direction, r.direction);
    const T facing = dot(scaled_down(r.direction, k), n);
    // Parallel ray, zero-area triangle (n = 0) or NaN input: a miss.
    if (!(std::fabs(facing) > T(0))) return std::nullopt;

    const T t = k == 0 ? dot(tri.a - r.origin, n) / facing : std::ldexp(dot(tri.a - r.origin, n) / facing, -k);
    if (!std::isfinite(t) || !range.surrounds(t)) return std::nullopt;

    // Step 2: is the plane hit inside all three edge half-planes? Points on
    // an edge (a coordinate of exactly 0) count as inside, so two triangles
    // sharing an edge leave no crack between them. NaN fails the test.
    const vec3<T> point = r.at(t);
    const vec3<T> bary = barycentric(tri, point);
    if (!(bary.x >= T(0) && bary.y >= T(0) && bary.z >= T(0))) return std::nullopt;

    hit_record<T> hit;
    hit.t = t;
    hit.point = point;
    // The outward normal, the side from which a -> b -> c runs counter-clockwise,
    // whichever side the ray comes from (hit.front_face(r) tells which, common/hit_record.hpp).
    hit.normal = n / length(n);  // n is already scaled to about 1: no overflow
    return hit;
}

template vec3<float> barycentric(const triangle<float>&, const vec3<float>&);
template vec3<double> barycentric(const triangle<double>&, const vec3<double>&);
template std::optional<hit_record<float>> intersect_triangle(const triangle<float>&, const ray<float>&,
                                                             const interval<float>&);
template std::optional<hit_record<double>> intersect_triangle(const triangle<double>&, const ray<double>&,
                                                              const interval<double>&);

}  // namespace rt::ch05
