// robust_sphere.cpp — reference solution for chapter 07, one function per step of the lecture.
#include "07-precision/robust_sphere.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

namespace rt::ch07 {

namespace {

template <class W>
W largest_magnitude(W a, W b, W c) {
    return std::max({std::fabs(a), std::fabs(b), std::fabs(c)});
}

// The power of two that brings m into [1, 2), or 0 when m is in a
// comfortable range, where products of four inputs (and their rounding
// errors) neither overflow nor sink into the subnormals.
template <class W>
int scale_exponent(W m) {
    constexpr int comfortable = std::numeric_limits<W>::max_exponent / 5;
    static const W top = std::ldexp(W(1), comfortable), bottom = std::ldexp(W(1), -comfortable);
    if (m < top && m >= bottom) return 0;
    return -std::ilogb(m);
}

// The outward unit normal from a centre-relative vector of any size:
// dividing by the largest component first keeps the squares in range.
template <class T>
vec3<T> unit(vec3<T> v) {
    v = v / largest_magnitude(v.x, v.y, v.z);
    return v / length(v);
}

}  // namespace

// Step 1: a, half_b and the quarter discriminant as pairs. By Lagrange's
// identity |f|^2 |d|^2 - (f.d)^2 = |f x d|^2, so a r^2 - |f x d|^2 is the
// discriminant over 4, with no two squares subtracted: each component of
// f x d is a difference of exact products, kept as a pair.
template <class T>
quadratic<T> quarter_discriminant(const scaled_problem<T>& p) {
    const auto& f = p.f;
    const auto& d = p.d;
    quadratic<T> q;
    q.a = two_prod(d[0], d[0]) + two_prod(d[1], d[1]) + two_prod(d[2], d[2]);
    q.half_b = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    const double_word<wide<T>> f_cross_d[3] = {f[1] * d[2] - f[2] * d[1], f[2] * d[0] - f[0] * d[2],
                                               f[0] * d[1] - f[1] * d[0]};
    const double_word<wide<T>> cross_squared =
        f_cross_d[0] * f_cross_d[0] + f_cross_d[1] * f_cross_d[1] + f_cross_d[2] * f_cross_d[2];
    q.quarter_disc = q.a * two_prod(p.radius, p.radius) - cross_squared;
    return q;
}

// Step 2: the stable pair. half_b and the square root get the same sign,
// so q is a sum, never a cancelling difference; Vieta (t0 t1 = c / a)
// gives the other root as c / q.
template <class T>
root_pair<T> stable_roots(wide<T> a, wide<T> half_b, wide<T> c, wide<T> quarter_disc) {
    const wide<T> q = -(half_b + std::copysign(std::sqrt(quarter_disc), half_b));
    root_pair<T> roots;  // q = 0: half_b = 0 and a tangent, the origin touches the sphere
    if (q != 0) {
        roots.near = c / q;
        roots.far = q / a;
        if (roots.far < roots.near) std::swap(roots.near, roots.far);  // the order depends on the sign of half_b
    }
    return roots;
}

// The triple-precision sum behind step 3. The formulation study and the
// numerics tests run this very file (formulations/chapter07_reference.cpp), so
// the robust sphere is written once, here, in one file as a submission is.
namespace sphere_pieces {

// c = f.f - r^2 from its exact pieces: (hi + lo)^2 = hi^2 + 2 hi lo + lo^2 for
// each component of f, each product split into value and error (two_prod), and
// r^2 as a pair, all summed as if in three times W's precision (sum_k3). For a
// ray origin a fraction of an ULP off the surface c is 10^9 times smaller than
// f.f; a double-word sum would leave it tens of ULPs of error, this about one.
template <class W>
W exact_constant_term(const double_word<W> (&f)[3], double_word<W> radius_squared) {
    std::array<W, 17> terms{};
    std::size_t n = 0;
    for (const double_word<W>& x : f) {
        const double_word<W> square = two_prod(x.hi, x.hi), cross = two_prod(x.hi, W(2) * x.lo);
        terms[n++] = square.hi, terms[n++] = square.lo, terms[n++] = cross.hi, terms[n++] = cross.lo;
        terms[n++] = x.lo * x.lo;  // about 2^-100 of f.f in double: its own rounding cannot matter
    }
    terms[n++] = -radius_squared.hi, terms[n++] = -radius_squared.lo;
    return sum_k3(terms);
}

}  // namespace sphere_pieces

// Step 3: c = f.f - r^2 from the exact pieces of (hi + lo)^2 = hi^2 +
// 2 hi lo + lo^2 and of r^2, added in triple precision. For an origin on
// the surface of a huge sphere c is a billion times smaller than f.f, and
// only a sum this careful leaves it an ULP or two of error.
template <class T>
wide<T> constant_term(const scaled_problem<T>& p) {
    return sphere_pieces::exact_constant_term(p.f, two_prod(p.radius, p.radius));
}

// Step 4: f = o - C exactly, and the powers of two that keep every square
// in range. The ray o + t d meets the sphere of radius r where the scaled
// ray 2^ef f + t' 2^ed d meets the sphere of radius 2^ef r: t = t' 2^(ed - ef).
template <class T>
scaled_problem<T> scaled_offset(const sphere<T>& s, const ray<T>& r) {
    using W = wide<T>;
    // Inputs within a factor 4 of W's largest number (possible only when W is
    // T, i.e. double data): o - C itself could overflow. Quartering o, C and
    // the radius first keeps it finite; it is exact except for bits below
    // 4 times the smallest subnormal, which no sum with such huge numbers keeps.
    const W quarter_of_max = W(std::numeric_limits<W>::max()) / 4;
    const W largest_input = std::max({largest_magnitude(W(r.origin.x), W(r.origin.y), W(r.origin.z)),
                                      largest_magnitude(W(s.center.x), W(s.center.y), W(s.center.z)), W(s.radius)});
    const int quartered = largest_input > quarter_of_max ? -2 : 0;
    const auto input = [quartered](T x) { return std::ldexp(W(x), quartered); };

    scaled_problem<T> p;
    for (int k = 0; k < 3; ++k) {
        p.f[k] = two_sum(input(r.origin[k]), -input(s.center[k]));  // an origin 0.01 above a radius of 1e6 keeps its 0.01
        p.d[k] = W(r.direction[k]);
    }
    p.radius = input(s.radius);

    const int scale_f = scale_exponent(std::max(largest_magnitude(p.f[0].hi, p.f[1].hi, p.f[2].hi), p.radius));
    p.ed = scale_exponent(largest_magnitude(p.d[0], p.d[1], p.d[2]));
    for (double_word<W>& x : p.f) x = scaled(x, scale_f);
    p.radius = std::ldexp(p.radius, scale_f);
    for (W& x : p.d) x = std::ldexp(x, p.ed);
    p.ef = scale_f + quartered;  // f and the radius are now 2^ef times the input's
    return p;
}

// Step 5: back to the caller's units, rounded to T once. A root within a
// few ULPs of T's largest number can be computed just above it (for double
// data ldexp then gives infinity): within 8 ULPs it is that largest number,
// the nearest T to a root that is really there.
template <class T>
T unscaled_root(wide<T> t_scaled, int exponent) {
    using W = wide<T>;
    const W t_max = W(std::numeric_limits<T>::max());
    const W t = std::ldexp(t_scaled, exponent);
    if (std::fabs(t) <= t_max) return T(t);
    const W quarter = std::ldexp(t_scaled, exponent - 2);  // finite near the top; far beyond it infinite: a miss
    const bool rounded_above_max = std::fabs(quarter) <= (t_max / 4) * (1 + 8 * W(std::numeric_limits<T>::epsilon()));
    return std::copysign(rounded_above_max ? std::numeric_limits<T>::max() : infinity<T>, T(t_scaled));
}

// Step 6: the steps in the order the computation needs them.
template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    using W = wide<T>;
    // Written as !(x > 0) so that NaN fails too.
    if (!(s.radius > T(0)) || !is_finite(r.origin) || !is_finite(r.direction) || !is_finite(s.center) ||
        !std::isfinite(s.radius))
        return std::nullopt;
    if (!(largest_magnitude(W(r.direction.x), W(r.direction.y), W(r.direction.z)) > 0))
        return std::nullopt;  // a zero direction meets nothing

    const scaled_problem<T> p = scaled_offset(s, r);
    const quadratic<T> eq = quarter_discriminant(p);
    if (is_negative(eq.quarter_disc)) return std::nullopt;
    const W c = constant_term(p);
    const root_pair<T> roots = stable_roots<T>(eq.a.value(), eq.half_b.value(), c, eq.quarter_disc.value());

    T t = unscaled_root<T>(roots.near, p.ed - p.ef);
    if (!range.surrounds(t)) {
        t = unscaled_root<T>(roots.far, p.ed - p.ef);  // e.g. the origin is inside the sphere
        if (!range.surrounds(t)) return std::nullopt;
    }

    hit_record<T> hit;
    hit.t = t;
    hit.point = r.at(t);
    // Centre-relative, f + t d: no far centre subtracted from a far point.
    // Computed from the scaled pieces so it neither overflows nor underflows.
    const W t_scaled = std::ldexp(W(t), p.ef - p.ed);
    vec3<W> outward;
    for (int k = 0; k < 3; ++k) outward[k] = p.f[k].hi + (p.f[k].lo + t_scaled * p.d[k]);
    if (!(largest_magnitude(outward.x, outward.y, outward.z) > W(0))) return std::nullopt;
    hit.normal = convert<T>(unit(outward));
    return hit;
}

#define RT_CH07_INSTANTIATE(T)                                                                                   \
    template quadratic<T> quarter_discriminant(const scaled_problem<T>&);                                       \
    template root_pair<T> stable_roots<T>(wide<T>, wide<T>, wide<T>, wide<T>);                                  \
    template wide<T> constant_term(const scaled_problem<T>&);                                                   \
    template scaled_problem<T> scaled_offset(const sphere<T>&, const ray<T>&);                                  \
    template T unscaled_root<T>(wide<T>, int);                                                                  \
    template std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>&, const ray<T>&, const interval<T>&);
RT_CH07_INSTANTIATE(float)
RT_CH07_INSTANTIATE(double)
RT_CH07_INSTANTIATE(long double)

}  // namespace rt::ch07
