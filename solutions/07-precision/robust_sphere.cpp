// robust_sphere.cpp — reference solution for chapter 07.
#include "07-precision/robust_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

namespace rt::ch07 {

namespace {

// The arithmetic is done in W: double for float data (every float is a
// double, so nothing is lost converting), T itself otherwise.
template <class T>
using wide = std::conditional_t<std::is_same_v<T, float>, double, T>;

// A number carried as the exact sum hi + lo of two W's ("double-word"):
// about twice the digits of W.
template <class W>
struct pair_sum {
    W hi = 0, lo = 0;
    W value() const { return hi + lo; }
};

// a + b = s + err exactly (Knuth's two-sum: six additions, no branch).
template <class W>
pair_sum<W> exact_sum(W a, W b) {
    const W s = a + b;
    const W b_part = s - a;
    return {s, (a - (s - b_part)) + (b - b_part)};
}

// a * b = p + err exactly: fma rounds only once, so it returns the
// rounding error of the product.
template <class W>
pair_sum<W> exact_product(W a, W b) {
    const W p = a * b;
    return {p, std::fma(a, b, -p)};
}

// Renormalise hi + lo (valid when |hi| >= |lo|).
template <class W>
pair_sum<W> renormalise(W hi, W lo) {
    const W s = hi + lo;
    return {s, lo - (s - hi)};
}

// x + y in pairs: high parts added exactly, low parts added, errors folded.
template <class W>
pair_sum<W> add(pair_sum<W> x, pair_sum<W> y) {
    pair_sum<W> s = exact_sum(x.hi, y.hi);
    const pair_sum<W> t = exact_sum(x.lo, y.lo);
    s = renormalise(s.hi, s.lo + t.hi);
    return renormalise(s.hi, s.lo + t.lo);
}

template <class W>
pair_sum<W> negate(pair_sum<W> x) {
    return {-x.hi, -x.lo};
}

template <class W>
pair_sum<W> multiply(pair_sum<W> x, pair_sum<W> y) {
    pair_sum<W> p = exact_product(x.hi, y.hi);
    return renormalise(p.hi, p.lo + (x.hi * y.lo + x.lo * y.hi));
}

template <class W>
pair_sum<W> multiply(pair_sum<W> x, W y) {
    pair_sum<W> p = exact_product(x.hi, y);
    return renormalise(p.hi, p.lo + x.lo * y);
}

// The sum of terms as if added in three times the precision and rounded
// once: two sweeps of exact_sum push every rounding error down the list
// without losing any of it (Ogita, Rump and Oishi's SumK with K = 3).
template <class W, std::size_t N>
W accurate_sum(W (&p)[N]) {
    for (int sweep = 0; sweep < 2; ++sweep) {
        for (std::size_t i = 1; i < N; ++i) {
            const pair_sum<W> s = exact_sum(p[i], p[i - 1]);
            p[i] = s.hi;
            p[i - 1] = s.lo;
        }
    }
    W sum = 0;
    for (std::size_t i = 0; i + 1 < N; ++i) sum += p[i];
    return sum + p[N - 1];
}

// Step 0: the power of two that brings m into [1, 2), or 0 when m is in a
// comfortable range where products of four inputs (and their rounding
// errors) neither overflow nor sink into the subnormals. Multiplying by a
// power of two is exact, so scaling changes no digit.
template <class W>
int scale_exponent(W m) {
    constexpr int comfortable = std::numeric_limits<W>::max_exponent / 5;
    static const W top = std::ldexp(W(1), comfortable), bottom = std::ldexp(W(1), -comfortable);
    if (m < top && m >= bottom) return 0;
    return -std::ilogb(m);
}

template <class W>
W largest(W a, W b, W c) {
    return std::max({std::fabs(a), std::fabs(b), std::fabs(c)});
}

// Step 3: c = f.f - r^2 from the exact pieces of (hi + lo)^2 = hi^2 +
// 2 hi lo + lo^2 and r^2, added in triple precision. For an origin on the
// surface of a huge sphere c is a billion times smaller than f.f, and only
// a sum this careful leaves it an ULP or two of error.
template <class W>
W distance_squared_minus_radius_squared(const pair_sum<W> (&f)[3], W radius) {
    W terms[17];
    std::size_t n = 0;
    for (const pair_sum<W>& x : f) {
        const pair_sum<W> square = exact_product(x.hi, x.hi), cross = exact_product(x.hi, W(2) * x.lo);
        terms[n++] = square.hi, terms[n++] = square.lo, terms[n++] = cross.hi, terms[n++] = cross.lo;
        terms[n++] = x.lo * x.lo;  // about 2^-100 of f.f: its own rounding cannot matter
    }
    const pair_sum<W> rr = exact_product(radius, radius);
    terms[n++] = -rr.hi, terms[n++] = -rr.lo;
    return accurate_sum(terms);
}

// The outward unit normal from a centre-relative vector of any size:
// dividing by the largest component first keeps the squares in range.
template <class T>
vec3<T> unit(vec3<T> v) {
    const T m = largest(v.x, v.y, v.z);
    v = v / m;
    return v / length(v);
}

}  // namespace

template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    using W = wide<T>;
    using P = pair_sum<W>;
    // Written as !(x > 0) so that NaN fails too.
    if (!(s.radius > T(0)) || !is_finite(r.origin) || !is_finite(r.direction) || !is_finite(s.center) ||
        !std::isfinite(s.radius))
        return std::nullopt;

    // Inputs within a factor 4 of W's largest number (possible only when W is
    // T, i.e. double data): o - C itself could overflow. Quartering o, C and
    // the radius first keeps it finite; it is exact except for bits below
    // 4 times the smallest subnormal, which no sum with such huge numbers keeps.
    const W top = W(std::numeric_limits<W>::max()) / 4;
    const int pre = std::max({largest(W(r.origin.x), W(r.origin.y), W(r.origin.z)),
                              largest(W(s.center.x), W(s.center.y), W(s.center.z)), W(s.radius)}) > top
                        ? -2
                        : 0;

    // f = o - C exactly, as pairs: an origin 0.01 above a sphere of radius
    // 1e6 keeps its 0.01 although o and C are a million units long.
    const auto part = [pre](T x) { return std::ldexp(W(x), pre); };
    P f[3] = {exact_sum(part(r.origin.x), -part(s.center.x)), exact_sum(part(r.origin.y), -part(s.center.y)),
              exact_sum(part(r.origin.z), -part(s.center.z))};
    W d[3] = {W(r.direction.x), W(r.direction.y), W(r.direction.z)};
    W radius = part(s.radius);

    // Step 0: scale f and the radius together, and d on its own, by powers
    // of two (a sphere of radius 1e-200 or 1e200 in double, a subnormal
    // direction). The ray o + t d meets the sphere where the scaled ray
    // 2^ef f + t' 2^ed d meets the sphere of radius 2^ef r: t = t' 2^(ed - ef).
    const W dmax = largest(d[0], d[1], d[2]);
    if (!(dmax > 0)) return std::nullopt;  // a zero direction meets nothing
    const int scale_f = scale_exponent(std::max(largest(f[0].hi, f[1].hi, f[2].hi), radius));
    const int ed = scale_exponent(dmax);
    for (P& x : f) x = {std::ldexp(x.hi, scale_f), std::ldexp(x.lo, scale_f)};
    radius = std::ldexp(radius, scale_f);
    const int ef = scale_f + pre;  // f and the radius are now 2^ef times the input's
    for (W& x : d) x = std::ldexp(x, ed);

    // Step 1: the discriminant through the perpendicular distance. By
    // Lagrange's identity |f|^2 |d|^2 - (f.d)^2 = |f x d|^2, so
    //     disc/4 = a r^2 - |f x d|^2,
    // where |f x d| / |d| is the distance from the centre to the ray's line
    // (the length of the foot vector, without subtracting any squares).
    // Each component of f x d is a difference of exact products, kept as a
    // pair: the discriminant keeps twice W's digits even for a grazing ray.
    const P a = add(add(exact_product(d[0], d[0]), exact_product(d[1], d[1])), exact_product(d[2], d[2]));
    const P half_b = add(add(multiply(f[0], d[0]), multiply(f[1], d[1])), multiply(f[2], d[2]));
    const P g[3] = {add(multiply(f[1], d[2]), negate(multiply(f[2], d[1]))),
                    add(multiply(f[2], d[0]), negate(multiply(f[0], d[2]))),
                    add(multiply(f[0], d[1]), negate(multiply(f[1], d[0])))};
    const P gg = add(add(multiply(g[0], g[0]), multiply(g[1], g[1])), multiply(g[2], g[2]));
    const P quarter_disc = add(multiply(a, exact_product(radius, radius)), negate(gg));
    // The sign of hi + lo is the sign of hi (or of lo when hi is 0).
    if (quarter_disc.hi < 0 || (quarter_disc.hi == 0 && quarter_disc.lo < 0)) return std::nullopt;

    // Step 3: the constant term, accurate even when f.f and r^2 agree in
    // nearly every digit.
    const W c = distance_squared_minus_radius_squared(f, radius);

    // Step 2: the stable pair. half_b and the square root get the same
    // sign, so q is a sum, never a cancelling difference; Vieta
    // (t0 t1 = c / a) gives the other root as c / q.
    const W hb = half_b.value(), aa = a.value();
    const W q = -(hb + std::copysign(std::sqrt(quarter_disc.value()), hb));
    W t_near = 0, t_far = 0;  // q = 0: half_b = 0 and a tangent, the origin touches the sphere
    if (q != W(0)) {
        t_near = c / q;
        t_far = q / aa;
        if (t_far < t_near) std::swap(t_near, t_far);  // the order depends on the sign of half_b
    }

    // Undo the scaling, and round to T once (beyond T's range: infinite,
    // which the range test rejects).
    // A root within a few ULPs of T's largest number can be computed just
    // above it (for double data ldexp then gives infinity): within 8 ULPs it
    // is that largest number, the nearest T to a root that is really there.
    const auto back = [&](W t) {
        const W t_max = W(std::numeric_limits<T>::max());
        const W x = std::ldexp(t, ed - ef);
        if (std::fabs(x) <= t_max) return T(x);
        const W quarter = std::ldexp(t, ed - ef - 2);  // finite near the top; far beyond it infinite: a miss
        const bool rounding = std::fabs(quarter) <= (t_max / 4) * (1 + 8 * W(std::numeric_limits<T>::epsilon()));
        return std::copysign(rounding ? std::numeric_limits<T>::max() : infinity<T>, T(t));
    };
    T t = back(t_near);
    if (!range.contains(t)) {
        t = back(t_far);  // e.g. the origin is inside the sphere
        if (!range.contains(t)) return std::nullopt;
    }

    hit_record<T> hit;
    hit.t = t;
    hit.point = r.at(t);
    // Centre-relative, f + t d: no far centre subtracted from a far point.
    // Computed from the scaled pieces so it neither overflows nor underflows.
    const W ts = std::ldexp(W(t), ef - ed);
    const vec3<W> outward(f[0].hi + (f[0].lo + ts * d[0]), f[1].hi + (f[1].lo + ts * d[1]),
                          f[2].hi + (f[2].lo + ts * d[2]));
    if (!(largest(outward.x, outward.y, outward.z) > W(0))) return std::nullopt;
    hit.normal = convert<T>(unit(outward));
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
