// robust_sphere.cpp — reference solution for chapter 07.
#include "robust_sphere.hpp"

#include <cmath>
#include <utility>

namespace rt::ch07 {

namespace {

// x * x as the exact sum hi + lo: hi is the rounded product, and fma, which
// rounds only once, recovers what the rounding threw away.
template <class T>
void exact_square(T x, T& hi, T& lo) {
    hi = x * x;
    lo = std::fma(x, x, -hi);
}

// a + b as the exact sum s + err (Knuth's two-sum: six additions, no branch).
template <class T>
void exact_sum(T a, T b, T& s, T& err) {
    s = a + b;
    const T b_part = s - a;
    err = (a - (s - b_part)) + (b - b_part);
}

// c = f.f - radius^2 without losing the digits the two squares share.
// The big parts are added exactly and their rounding errors collected, so
// c comes out as if computed in twice the precision of T, then rounded.
template <class T>
T distance_squared_minus_radius_squared(const vec3<T>& f, T radius) {
    T xx, xx_lo, yy, yy_lo, zz, zz_lo, rr, rr_lo;
    exact_square(f.x, xx, xx_lo);
    exact_square(f.y, yy, yy_lo);
    exact_square(f.z, zz, zz_lo);
    exact_square(radius, rr, rr_lo);
    T s1, e1, s2, e2, s3, e3;
    exact_sum(xx, yy, s1, e1);
    exact_sum(s1, zz, s2, e2);
    exact_sum(s2, -rr, s3, e3);
    return s3 + (((e1 + e2) + e3) + ((xx_lo + yy_lo + zz_lo) - rr_lo));
}

}  // namespace

template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    const vec3<T>& d = r.direction;
    const T radius = s.radius;
    const T a = dot(d, d);
    // Written as !(x > 0) so that NaN fails too.
    if (!(a > T(0)) || !(radius > T(0))) return std::nullopt;

    const vec3<T> f = r.origin - s.center;  // centre to ray origin
    const T half_b = dot(f, d);

    // 1. Foot of the perpendicular from the centre onto the ray's line. The
    // subtraction happens on vectors, before anything is squared, so a far
    // sphere's large |f| cancels while the numbers still carry all their bits.
    const vec3<T> foot = f - (half_b / a) * d;
    const T quarter_disc = a * (radius * radius - dot(foot, foot));
    if (!(quarter_disc >= T(0))) return std::nullopt;  // the line passes farther than radius (or NaN)

    // 3. The constant term, accurate even when f.f and radius^2 nearly agree.
    const T c = distance_squared_minus_radius_squared(f, radius);

    // 2. The stable pair: half_b and the square root get the same sign, so
    // q is a sum, never a cancelling difference. Vieta (t0 t1 = c / a) gives
    // the other root as c / q.
    const T q = -(half_b + std::copysign(std::sqrt(quarter_disc), half_b));
    T t_near, t_far;
    if (q == T(0)) {
        t_near = t_far = T(0);  // half_b = 0 and a tangent: the origin touches the sphere
    } else {
        t_near = c / q;
        t_far = q / a;
        // Which of the two is nearer depends on the sign of half_b.
        if (t_far < t_near) std::swap(t_near, t_far);
    }

    T t = t_near;
    if (!range.contains(t)) {
        t = t_far;  // e.g. the origin is inside the sphere
        if (!range.contains(t)) return std::nullopt;
    }
    if (!std::isfinite(t)) return std::nullopt;

    hit_record<T> hit;
    hit.t = t;
    hit.point = r.at(t);
    // Centre-relative, (f + t d) / radius avoids subtracting a far centre
    // from a far point; renormalising keeps the length 1 to the last bit
    // that T can hold.
    const vec3<T> outward = f + t * d;
    const T len = length(outward);
    if (!(len > T(0)) || !std::isfinite(len)) return std::nullopt;
    hit.normal = outward / len;
    return hit;
}

template std::optional<hit_record<float>> intersect_sphere_robust(const sphere<float>&, const ray<float>&,
                                                                  const interval<float>&);
template std::optional<hit_record<double>> intersect_sphere_robust(const sphere<double>&, const ray<double>&,
                                                                   const interval<double>&);
template std::optional<hit_record<long double>> intersect_sphere_robust(const sphere<long double>&,
                                                                        const ray<long double>&,
                                                                        const interval<long double>&);

}  // namespace rt::ch07
