// reference.cpp — MPFR evaluation of the sphere, plane and triangle answers.
#include "reference.hpp"

#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <vector>

namespace rt::study {
namespace {

// One MPFR number with its own precision; released when it goes out of scope.
class big {
public:
    explicit big(mpfr_prec_t bits) { mpfr_init2(v_, bits); }
    big(mpfr_prec_t bits, long double x) : big(bits) { mpfr_set_ld(v_, x, MPFR_RNDN); }
    big(big&& other) noexcept {
        mpfr_init2(v_, mpfr_get_prec(other.v_));
        mpfr_swap(v_, other.v_);
    }
    ~big() { mpfr_clear(v_); }
    big(const big&) = delete;
    big& operator=(const big&) = delete;
    mpfr_ptr get() { return v_; }
    mpfr_srcptr get() const { return v_; }
    int sign() const { return mpfr_sgn(v_); }
    long double ld() const { return mpfr_get_ld(v_, MPFR_RNDN); }

private:
    mpfr_t v_;
};

// Enough bits that sums of products of up to four inputs are exact: four
// times the spread of the exponents, plus four significands, plus margin.
template <class T>
mpfr_prec_t exact_bits(std::initializer_list<T> values) {
    int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
    for (T v : values) {
        if (v == 0 || !std::isfinite(v)) continue;
        int e = std::ilogb(v);
        lo = std::min(lo, e);
        hi = std::max(hi, e);
    }
    int spread = lo <= hi ? hi - lo : 0;
    int digits = std::numeric_limits<T>::digits;
    return static_cast<mpfr_prec_t>(4 * (spread + digits) + 128);
}

template <class T>
double round_to(const big& x) {
    if constexpr (sizeof(T) == sizeof(float))
        return static_cast<double>(mpfr_get_flt(x.get(), MPFR_RNDN));
    else
        return mpfr_get_d(x.get(), MPFR_RNDN);
}

// out = a - b for T inputs (exact at the chosen precision).
template <class T>
void set_difference(big& out, T a, T b) {
    big x(mpfr_get_prec(out.get()), a);
    mpfr_sub_d(out.get(), x.get(), static_cast<double>(b), MPFR_RNDN);
}

// out = x . y for three-component arrays of big numbers.
void dot3(big& out, big* x, big* y, mpfr_prec_t bits) {
    big p(bits);
    mpfr_mul(out.get(), x[0].get(), y[0].get(), MPFR_RNDN);
    for (int i = 1; i < 3; ++i) {
        mpfr_mul(p.get(), x[i].get(), y[i].get(), MPFR_RNDN);
        mpfr_add(out.get(), out.get(), p.get(), MPFR_RNDN);
    }
}

// out = x cross y
void cross3(big* out, big* x, big* y, mpfr_prec_t bits) {
    big p(bits);
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        mpfr_mul(out[i].get(), x[j].get(), y[k].get(), MPFR_RNDN);
        mpfr_mul(p.get(), x[k].get(), y[j].get(), MPFR_RNDN);
        mpfr_sub(out[i].get(), out[i].get(), p.get(), MPFR_RNDN);
    }
}

template <class T>
bool inside_range(const big& t, const interval<T>& range) {
    // NaN bounds make every comparison false, as in interval::surrounds.
    if (std::isnan(range.min) || std::isnan(range.max)) return false;
    return mpfr_cmp_d(t.get(), static_cast<double>(range.min)) > 0 &&
           mpfr_cmp_d(t.get(), static_cast<double>(range.max)) < 0;
}

template <class T>
T comp(const vec3<T>& v, int i) {
    return i == 0 ? v.x : (i == 1 ? v.y : v.z);
}

// Three big numbers holding the exact difference a - b of two vectors.
template <class T>
std::vector<big> difference(const vec3<T>& a, const vec3<T>& b, mpfr_prec_t bits) {
    std::vector<big> out;
    out.reserve(3);
    for (int i = 0; i < 3; ++i) {
        out.emplace_back(bits);
        set_difference(out.back(), comp(a, i), comp(b, i));
    }
    return out;
}

template <class T>
std::vector<big> exact(const vec3<T>& a, mpfr_prec_t bits) {
    std::vector<big> out;
    out.reserve(3);
    for (int i = 0; i < 3; ++i) out.emplace_back(bits, static_cast<long double>(comp(a, i)));
    return out;
}

}  // namespace

template <class T>
reference_answer sphere_reference(const ray<T>& r, const sphere<T>& s, const interval<T>& range) {
    reference_answer ans;
    if (!is_finite(r.origin) || !is_finite(r.direction) || !is_finite(s.center) || !std::isfinite(s.radius) ||
        !(s.radius > 0))
        return ans;
    const vec3<T>&o = r.origin, &d = r.direction, &C = s.center;
    mpfr_prec_t bits = exact_bits<T>({o.x, o.y, o.z, d.x, d.y, d.z, C.x, C.y, C.z, s.radius});
    std::vector<big> f = difference(o, C, bits), dv = exact(d, bits);
    big a(bits), h(bits), c(bits), r2(bits), disc(bits), tmp(bits);
    dot3(a, dv.data(), dv.data(), bits);
    if (a.sign() == 0) return ans;  // zero direction
    dot3(h, f.data(), dv.data(), bits);
    dot3(c, f.data(), f.data(), bits);
    mpfr_set_d(r2.get(), static_cast<double>(s.radius), MPFR_RNDN);
    mpfr_sqr(r2.get(), r2.get(), MPFR_RNDN);
    mpfr_sub(c.get(), c.get(), r2.get(), MPFR_RNDN);
    // disc = h^2 - a c, exact
    mpfr_sqr(disc.get(), h.get(), MPFR_RNDN);
    mpfr_mul(tmp.get(), a.get(), c.get(), MPFR_RNDN);
    mpfr_sub(disc.get(), disc.get(), tmp.get(), MPFR_RNDN);
    if (disc.sign() < 0) return ans;

    // Stable pair: q = -(h + sign(h) sqrt(disc)), roots c/q and q/a.
    big q(bits), t0(bits), t1(bits);
    mpfr_sqrt(q.get(), disc.get(), MPFR_RNDN);
    if (h.sign() < 0) mpfr_neg(q.get(), q.get(), MPFR_RNDN);
    mpfr_add(q.get(), q.get(), h.get(), MPFR_RNDN);
    mpfr_neg(q.get(), q.get(), MPFR_RNDN);
    if (q.sign() == 0) {
        mpfr_set_zero(t0.get(), 1);
        mpfr_set_zero(t1.get(), 1);
    } else {
        mpfr_div(t0.get(), c.get(), q.get(), MPFR_RNDN);
        mpfr_div(t1.get(), q.get(), a.get(), MPFR_RNDN);
    }
    if (mpfr_cmp(t1.get(), t0.get()) < 0) mpfr_swap(t0.get(), t1.get());
    ans.has_roots = true;
    ans.t_near = t0.ld();
    ans.t_far = t1.ld();
    for (big* t : {&t0, &t1}) {
        // A crossing beyond the largest T is no answer a routine in T can
        // give (the contract forbids infinity): it counts as no crossing.
        if (inside_range(*t, range) && std::isfinite(round_to<T>(*t))) {
            ans.hit = true;
            ans.t = t->ld();
            ans.t_rounded = round_to<T>(*t);
            break;
        }
    }
    return ans;
}

template <class T>
reference_answer plane_reference(const ray<T>& r, const plane<T>& p, const interval<T>& range) {
    reference_answer ans;
    if (!is_finite(r.origin) || !is_finite(r.direction) || !is_finite(p.point) || !is_finite(p.normal)) return ans;
    const vec3<T>&o = r.origin, &d = r.direction, &n = p.normal, &q = p.point;
    mpfr_prec_t bits = exact_bits<T>({o.x, o.y, o.z, d.x, d.y, d.z, n.x, n.y, n.z, q.x, q.y, q.z});
    std::vector<big> qo = difference(q, o, bits), dv = exact(d, bits), nv = exact(n, bits);
    big num(bits), den(bits), t(bits);
    dot3(den, dv.data(), nv.data(), bits);
    if (den.sign() == 0) return ans;
    dot3(num, qo.data(), nv.data(), bits);
    mpfr_div(t.get(), num.get(), den.get(), MPFR_RNDN);
    ans.has_roots = true;
    ans.t_near = ans.t_far = t.ld();
    if (inside_range(t, range) && std::isfinite(round_to<T>(t))) {
        ans.hit = true;
        ans.t = t.ld();
        ans.t_rounded = round_to<T>(t);
    }
    return ans;
}

template <class T>
reference_answer triangle_reference(const ray<T>& r, const triangle<T>& tri, const interval<T>& range) {
    reference_answer ans;
    if (!is_finite(r.origin) || !is_finite(r.direction) || !is_finite(tri.a) || !is_finite(tri.b) ||
        !is_finite(tri.c))
        return ans;
    const vec3<T>&o = r.origin, &d = r.direction;
    mpfr_prec_t bits = exact_bits<T>({o.x, o.y, o.z, d.x, d.y, d.z, tri.a.x, tri.a.y, tri.a.z, tri.b.x, tri.b.y,
                                      tri.b.z, tri.c.x, tri.c.y, tri.c.z});
    std::vector<big> A = difference(tri.a, o, bits), B = difference(tri.b, o, bits), C = difference(tri.c, o, bits);
    std::vector<big> dv = exact(d, bits);
    std::vector<big> cr;
    for (int i = 0; i < 3; ++i) cr.emplace_back(bits);
    // Signed volumes of the line with each edge: the line crosses the
    // triangle when none of them has a sign opposite to another.
    big vol[3] = {big(bits), big(bits), big(bits)};
    cross3(cr.data(), B.data(), C.data(), bits);
    dot3(vol[0], dv.data(), cr.data(), bits);
    cross3(cr.data(), C.data(), A.data(), bits);
    dot3(vol[1], dv.data(), cr.data(), bits);
    cross3(cr.data(), A.data(), B.data(), bits);
    dot3(vol[2], dv.data(), cr.data(), bits);
    bool neg = vol[0].sign() < 0 || vol[1].sign() < 0 || vol[2].sign() < 0;
    bool pos = vol[0].sign() > 0 || vol[1].sign() > 0 || vol[2].sign() > 0;
    if (neg && pos) return ans;
    // The three volumes add up to d.n, with n = (b - a) x (c - a); the
    // volume of a with the triangle is (a - o).n, so t = that / d.n.
    big den(bits), num(bits), t(bits);
    mpfr_add(den.get(), vol[0].get(), vol[1].get(), MPFR_RNDN);
    mpfr_add(den.get(), den.get(), vol[2].get(), MPFR_RNDN);
    if (den.sign() == 0) return ans;  // degenerate, or the ray lies in the plane
    // (a - o) . ((b - o) x (c - o)) = (a - o) . n
    cross3(cr.data(), B.data(), C.data(), bits);
    dot3(num, A.data(), cr.data(), bits);
    mpfr_div(t.get(), num.get(), den.get(), MPFR_RNDN);
    ans.has_roots = true;
    ans.t_near = ans.t_far = t.ld();
    if (inside_range(t, range) && std::isfinite(round_to<T>(t))) {
        ans.hit = true;
        ans.t = t.ld();
        ans.t_rounded = round_to<T>(t);
    }
    return ans;
}

template <class T>
double off_plane_ulps(const plane<T>& p, const vec3<T>& x) {
    if (!is_finite(x)) return std::numeric_limits<double>::infinity();
    const vec3<T>&n = p.normal, &q = p.point;
    mpfr_prec_t bits = exact_bits<T>({x.x, x.y, x.z, n.x, n.y, n.z, q.x, q.y, q.z});
    std::vector<big> xq = difference(x, q, bits), nv = exact(n, bits);
    big num(bits), len(bits);
    dot3(num, xq.data(), nv.data(), bits);
    dot3(len, nv.data(), nv.data(), bits);
    mpfr_sqrt(len.get(), len.get(), MPFR_RNDN);
    mpfr_div(num.get(), num.get(), len.get(), MPFR_RNDN);
    mpfr_abs(num.get(), num.get(), MPFR_RNDN);
    // The scale of the question: the larger of the point and the plane's
    // anchor point (a point cannot be placed closer than their ULPs allow).
    T largest = std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z), std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
    if (largest == 0) largest = std::numeric_limits<T>::min();
    // One ULP of the largest coordinate.
    long double ulp = std::ldexp(1.0L, std::ilogb(largest) - (std::numeric_limits<T>::digits - 1));
    return static_cast<double>(num.ld() / ulp);
}

#define RT_INSTANTIATE(T)                                                                                 \
    template reference_answer sphere_reference<T>(const ray<T>&, const sphere<T>&, const interval<T>&);   \
    template reference_answer plane_reference<T>(const ray<T>&, const plane<T>&, const interval<T>&);     \
    template reference_answer triangle_reference<T>(const ray<T>&, const triangle<T>&, const interval<T>&); \
    template double off_plane_ulps<T>(const plane<T>&, const vec3<T>&);
RT_INSTANTIATE(float)
RT_INSTANTIATE(double)
#undef RT_INSTANTIATE

}  // namespace rt::study
