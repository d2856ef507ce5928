// Hidden tests for chapter 04 (run by the autograder only).
//
// Failure messages name the idea that went wrong but never the expected
// numbers: every check is a plain bool computed beforehand.
#include "04-plane/plane.hpp"

#include "test_support.hpp"

#include <cmath>
#include <limits>
#include <random>

using namespace rt;
using rt::ch04::intersect_plane;

namespace {

template <class T>
interval<T> ahead() {
    return {T(0), infinity<T>};
}

template <class T>
long double tolerance() {
    return sizeof(T) == 4 ? 2e-4L : 1e-10L;
}

template <class T>
long double epsilon() {
    return std::numeric_limits<T>::epsilon();
}

// t of the crossing from the rounded inputs, in long double, with the plane's
// normal used as given (its length cancels). Returns false when d . n == 0.
// `spread` receives a scale for the rounding error of any sensible float or
// double evaluation: (sum |(p0 - o)_i n_i| + |t| sum |d_i n_i|) / |d . n|.
template <class T>
bool reference_t(const plane<T>& p, const ray<T>& r, long double& t, long double& spread) {
    long double num = 0, den = 0, num_abs = 0, den_abs = 0;
    for (int i = 0; i < 3; ++i) {
        long double a = (long double)p.point[i] - (long double)r.origin[i];
        num += a * p.normal[i];
        num_abs += std::fabs(a * p.normal[i]);
        den += (long double)r.direction[i] * p.normal[i];
        den_abs += std::fabs((long double)r.direction[i] * p.normal[i]);
    }
    if (den == 0) return false;
    t = num / den;
    spread = (num_abs + std::fabs(t) * den_abs) / std::fabs(den);
    return true;
}

template <class T>
bool near_t(const std::optional<hit_record<T>>& hit, long double want) {
    return hit && std::isfinite(hit->t) && std::fabs((long double)hit->t - want) <= tolerance<T>() * (1 + std::fabs(want));
}

template <class T>
bool is_unit(const vec3<T>& v) {
    long double x = v.x, y = v.y, z = v.z;
    return std::fabs(std::sqrt(x * x + y * y + z * z) - 1) <= tolerance<T>();
}

// The normal is the plane's own, at unit length: it points the way p.normal
// does, whichever side the ray comes from (the side is hit.front_face(r),
// common/hit_record.hpp's rule, not the exercise's business).
template <class T>
bool good_normal(const hit_record<T>& hit, const plane<T>& p) {
    if (!is_unit(hit.normal)) return false;
    const vec3<long double> n = convert<long double>(p.normal), h = convert<long double>(hit.normal);
    const long double cos_angle = dot(n, h) / std::sqrt(dot(n, n));
    return std::fabs(cos_angle - 1) <= 10 * tolerance<T>();
}

template <class T>
bool point_on_ray(const hit_record<T>& hit, const ray<T>& r) {
    const vec3<T> want = r.at(hit.t);
    const T scale = std::fmax(T(1), std::fmax(std::fabs(want.x), std::fmax(std::fabs(want.y), std::fabs(want.z))));
    return std::fabs(hit.point.x - want.x) <= T(tolerance<T>()) * scale &&
           std::fabs(hit.point.y - want.y) <= T(tolerance<T>()) * scale &&
           std::fabs(hit.point.z - want.z) <= T(tolerance<T>()) * scale;
}

}  // namespace

TEST_CASE_TEMPLATE("hidden: straight-on rays hit at the right t", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const plane<T> wall{{3, 5, -2}, {0, 0, 1}, 0};
    const plane<T> side{{T(-1.5), 0, 0}, {-1, 0, 0}, 0};
    bool ok = near_t(intersect_plane(ground, ray<T>{{2, 5, -1}, {0, -1, 0}}, ahead<T>()), 5) &&
              near_t(intersect_plane(wall, ray<T>{{0, 0, 6}, {0, 0, -1}}, ahead<T>()), 8) &&
              near_t(intersect_plane(side, ray<T>{{1, 2, 3}, {-1, 0, 0}}, ahead<T>()), 2.5L) &&
              near_t(intersect_plane(ground, ray<T>{{0, T(0.25), 0}, {0, -1, 0}}, ahead<T>()), 0.25L);
    CHECK_MESSAGE(ok, "a ray heading straight at a plane hits at t = (p0 - o) . n / (d . n)");
}

TEST_CASE_TEMPLATE("hidden: oblique rays hit at the right t and point", T, RT_SCALARS) {
    const plane<T> tilted{{1, 1, 1}, {1, 1, 1}, 0};  // x + y + z = 3
    const ray<T> r1{{0, 0, 0}, {1, 2, 3}};           // 6 t = 3
    const ray<T> r2{{0, 4, 0}, {T(0.5), -2, T(0.25)}};
    const plane<T> ground{{0, -1, 0}, {0, 1, 0}, 0};
    auto h1 = intersect_plane(tilted, r1, ahead<T>());
    auto h2 = intersect_plane(ground, r2, ahead<T>());  // 4 - 2 t = -1
    bool ok = near_t(h1, 0.5L) && near_t(h2, 2.5L) && point_on_ray(*h1, r1) && point_on_ray(*h2, r2);
    CHECK_MESSAGE(ok, "an oblique ray meets the plane at t = (p0 - o) . n / (d . n), the point being r(t)");
}

TEST_CASE_TEMPLATE("hidden: the direction need not be unit length", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    bool ok = near_t(intersect_plane(ground, ray<T>{{0, 4, 0}, {0, -8, 0}}, ahead<T>()), 0.5L) &&
              near_t(intersect_plane(ground, ray<T>{{0, 4, 0}, {3, T(-0.5), 1}}, ahead<T>()), 8);
    CHECK_MESSAGE(ok, "t counts steps of the direction d, not distance: keep d . n as it is");
}

TEST_CASE_TEMPLATE("hidden: parallel rays are misses", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const plane<T> tilted{{1, 1, 1}, {1, 1, 1}, 0};
    bool ok = !intersect_plane(ground, ray<T>{{0, 1, 0}, {1, 0, 0}}, ahead<T>()).has_value() &&
              !intersect_plane(ground, ray<T>{{0, -1, 0}, {0, 0, -1}}, ahead<T>()).has_value() &&
              !intersect_plane(tilted, ray<T>{{0, 0, 0}, {1, -1, 0}}, ahead<T>()).has_value() &&
              !intersect_plane(ground, ray<T>{{0, 1, 0}, {1, 0, 0}}, interval<T>{-infinity<T>, infinity<T>}).has_value();
    CHECK_MESSAGE(ok, "d . n = 0: a ray parallel to the plane never reaches it, which is a miss, never an infinity");
}

TEST_CASE_TEMPLATE("hidden: rays lying in the plane are misses", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const plane<T> tilted{{1, 1, 1}, {1, 1, 1}, 0};
    bool ok = !intersect_plane(ground, ray<T>{{5, 0, -3}, {1, 0, 1}}, ahead<T>()).has_value() &&
              !intersect_plane(tilted, ray<T>{{3, 0, 0}, {-1, 1, 0}}, ahead<T>()).has_value() &&
              !intersect_plane(ground, ray<T>{{5, 0, -3}, {1, 0, 1}}, interval<T>{-infinity<T>, infinity<T>}).has_value();
    CHECK_MESSAGE(ok, "a ray inside the plane gives 0 / 0 = NaN: it must be a miss, never a NaN hit");
}

TEST_CASE_TEMPLATE("hidden: nearly parallel rays still hit far away", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    bool ok = near_t(intersect_plane(ground, ray<T>{{0, 1, 0}, {1, T(-0.001), 0}}, ahead<T>()), 1000) &&
              near_t(intersect_plane(ground, ray<T>{{0, 2, 0}, {0, T(-0.0001), -1}}, ahead<T>()), 20000);
    CHECK_MESSAGE(ok, "only d . n == 0 is parallel: a small d . n is a genuine hit far away, not a miss");
}

TEST_CASE_TEMPLATE("hidden: a plane hit from behind keeps its own normal", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const plane<T> tilted{{1, 1, 1}, {1, 1, 1}, 0};
    const ray<T> below{{0, -3, 0}, {0, 1, 0}};
    const ray<T> behind{{0, 0, 0}, {1, 1, 1}};
    auto h1 = intersect_plane(ground, below, ahead<T>());
    auto h2 = intersect_plane(tilted, behind, ahead<T>());
    bool ok = near_t(h1, 3) && near_t(h2, 1) && good_normal(*h1, ground) && good_normal(*h2, tilted);
    CHECK_MESSAGE(ok, "from behind the plane (d . n > 0) it is still a hit, and the normal is still the plane's own "
                      "(the one face rule, not the exercise, turns it towards the ray)");
}

TEST_CASE_TEMPLATE("hidden: the normal is the plane's own on either side", T, RT_SCALARS) {
    std::mt19937 rng(404);
    std::uniform_real_distribution<double> u(-1, 1);
    int bad = 0, hits = 0, from_behind = 0;
    for (int i = 0; i < 500; ++i) {
        const plane<T> p{{T(u(rng)), T(u(rng)), T(u(rng))}, {T(u(rng)), T(u(rng)), T(u(rng))}, 0};
        const ray<T> r{{T(3 * u(rng)), T(3 * u(rng)), T(3 * u(rng))}, {T(u(rng)), T(u(rng)), T(u(rng))}};
        if (!(length(p.normal) > T(0.1)) || !(std::fabs(dot(normalize(p.normal), normalize(r.direction))) > T(0.05)))
            continue;
        auto hit = intersect_plane(p, r, interval<T>{-infinity<T>, infinity<T>});
        if (!hit) { ++bad; continue; }
        ++hits;
        if (dot(p.normal, r.direction) > T(0)) ++from_behind;
        if (!good_normal(*hit, p)) ++bad;
    }
    CHECK(hits > 300);
    CHECK(from_behind > 100);
    CHECK_MESSAGE(bad == 0, "the hit's normal must be unit length and point the way the plane's normal does, from "
                            "either side");
}

TEST_CASE_TEMPLATE("hidden: the normal is unit length for any plane normal", T, RT_SCALARS) {
    const ray<T> r{{0, 5, 0}, {0, -1, 0}};
    bool ok = true;
    for (T len : {T(0.001), T(0.5), T(3), T(250)}) {
        const plane<T> p{{0, 0, 0}, {0, len, 0}, 0};
        auto hit = intersect_plane(p, r, ahead<T>());
        ok = ok && near_t(hit, 5) && good_normal(*hit, p);
    }
    const plane<T> slanted{{0, 0, 0}, {3, 4, 0}, 0};
    auto hit = intersect_plane(slanted, r, ahead<T>());
    ok = ok && near_t(hit, 5) && good_normal(*hit, slanted);
    CHECK_MESSAGE(ok, "the plane's normal need not be unit length: t is unaffected, but the reported normal must be normalised");
}

TEST_CASE_TEMPLATE("hidden: extreme normal lengths still give the right hit", T, RT_SCALARS) {
    // Normals so short or so long that n . n underflows or overflows in T,
    // down to a subnormal length.
    const T tiny = sizeof(T) == 4 ? T(1e-30) : T(1e-200);
    const T subnormal = std::numeric_limits<T>::denorm_min() * T(1024);
    const T huge = sizeof(T) == 4 ? T(1e30) : T(1e200);
    const ray<T> r{{1, 2, 3}, {0, -1, 0}};
    bool ok = true;
    for (T len : {tiny, subnormal, huge}) {
        const plane<T> p{{0, 0, 0}, {0, len, 0}, 0};
        auto hit = intersect_plane(p, r, ahead<T>());
        ok = ok && near_t(hit, 2) && good_normal(*hit, p);
    }
    CHECK_MESSAGE(ok, "a normal of extreme length still describes a plane: normalise it without overflow or underflow");
}

TEST_CASE_TEMPLATE("hidden: planes behind the origin are not hit", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const plane<T> tilted{{1, 1, 1}, {1, 1, 1}, 0};
    bool ok = !intersect_plane(ground, ray<T>{{0, 2, 0}, {0, 1, 0}}, ahead<T>()).has_value() &&
              !intersect_plane(ground, ray<T>{{0, -2, 0}, {1, -1, 1}}, ahead<T>()).has_value() &&
              !intersect_plane(tilted, ray<T>{{0, 0, 0}, {-1, -2, -3}}, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "a negative t is a crossing behind the ray's origin: only tmin < t counts");
}

TEST_CASE_TEMPLATE("hidden: perspective rays skip hits before the image plane", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const auto front = interval<T>::in_front_of_image_plane();
    bool ok = !intersect_plane(ground, ray<T>{{0, T(0.5), 0}, {0, -1, 0}}, front).has_value() &&
              near_t(intersect_plane(ground, ray<T>{{0, T(1.5), 0}, {0, -1, 0}}, front), 1.5L);
    CHECK_MESSAGE(ok, "with the image plane at t = 1, a crossing at t <= 1 is not visible");
}

TEST_CASE_TEMPLATE("hidden: hits beyond tmax are rejected", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const ray<T> r{{0, 5, 0}, {0, -1, 0}};
    bool ok = !intersect_plane(ground, r, interval<T>{0, T(4.5)}).has_value() &&
              near_t(intersect_plane(ground, r, interval<T>{0, T(5.5)}), 5) &&
              !intersect_plane(ground, r, interval<T>{T(-10), T(1)}).has_value();
    CHECK_MESSAGE(ok, "a hit counts only when tmin < t < tmax: a crossing past tmax is not in range");
}

TEST_CASE_TEMPLATE("hidden: the interval is open at both ends", T, RT_SCALARS) {
    // From y = 3 straight down the crossing is exactly t = 3 in both precisions.
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const ray<T> r{{0, 3, 0}, {0, -1, 0}};
    bool ok = !intersect_plane(ground, r, interval<T>{0, 3}).has_value() &&
              !intersect_plane(ground, r, interval<T>{3, 10}).has_value() &&
              near_t(intersect_plane(ground, r, interval<T>{T(2.5), T(3.5)}), 3);
    CHECK_MESSAGE(ok, "the rule is strict, tmin < t < tmax: a crossing exactly at tmin or tmax does not count");
}

TEST_CASE_TEMPLATE("hidden: an origin on the plane does not hit it again", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    bool ok = !intersect_plane(ground, ray<T>{{2, 0, 1}, {0, 1, 0}}, ahead<T>()).has_value() &&
              !intersect_plane(ground, ray<T>{{2, 0, 1}, {1, -1, 0}}, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "a ray leaving the plane has its crossing at t = 0, which is not > tmin = 0");
}

TEST_CASE_TEMPLATE("hidden: the object field is left at -1", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 7};
    auto hit = intersect_plane(ground, ray<T>{{0, 1, 0}, {0, -1, 0}}, ahead<T>());
    bool ok = hit.has_value() && hit->object == -1;
    CHECK_MESSAGE(ok, "intersect_plane does not know the plane's index in a scene: leave object at -1");
}

TEST_CASE_TEMPLATE("hidden: NaN inputs are misses", T, RT_SCALARS) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    const ray<T> down{{0, 2, 0}, {0, -1, 0}};
    const auto all = interval<T>{-infinity<T>, infinity<T>};
    bool ok = !intersect_plane(ground, ray<T>{{nan, 2, 0}, {0, -1, 0}}, all).has_value() &&
              !intersect_plane(ground, ray<T>{{0, nan, 0}, {0, -1, 0}}, all).has_value() &&
              !intersect_plane(ground, ray<T>{{0, 2, 0}, {0, nan, 0}}, all).has_value() &&
              !intersect_plane(plane<T>{{0, nan, 0}, {0, 1, 0}, 0}, down, all).has_value() &&
              !intersect_plane(plane<T>{{0, 0, 0}, {nan, 1, 0}, 0}, down, all).has_value();
    CHECK_MESSAGE(ok, "a NaN anywhere in the ray or the plane must give a miss: comparisons written so NaN fails them");
}

TEST_CASE_TEMPLATE("hidden: a zero direction is a miss", T, RT_SCALARS) {
    const plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    bool ok = !intersect_plane(ground, ray<T>{{0, 2, 0}, {0, 0, 0}}, interval<T>{-infinity<T>, infinity<T>}).has_value() &&
              !intersect_plane(ground, ray<T>{{0, 0, 0}, {0, 0, 0}}, interval<T>{-infinity<T>, infinity<T>}).has_value();
    CHECK_MESSAGE(ok, "a zero direction has d . n = 0 like a parallel ray: a miss, never a NaN or infinite t");
}

TEST_CASE_TEMPLATE("hidden: huge and tiny coordinates", T, RT_SCALARS) {
    const T big = sizeof(T) == 4 ? T(1e15) : T(1e150);
    const T small = sizeof(T) == 4 ? T(1e-15) : T(1e-150);
    bool ok = near_t(intersect_plane(plane<T>{{0, big, 0}, {0, 1, 0}, 0}, ray<T>{{0, 0, 0}, {0, 1, 0}}, ahead<T>()),
                     (long double)big) &&
              near_t(intersect_plane(plane<T>{{0, small, 0}, {0, 1, 0}, 0}, ray<T>{{0, 0, 0}, {0, 1, 0}}, ahead<T>()),
                     (long double)small) &&
              near_t(intersect_plane(plane<T>{{0, 0, 0}, {0, 1, 0}, 0}, ray<T>{{0, big, 0}, {0, -big, 0}}, ahead<T>()), 1);
    CHECK_MESSAGE(ok, "very large and very small distances are still plain crossings: no overflow, no rounding to zero");
}

TEST_CASE_TEMPLATE("hidden: random rays agree with a higher-precision answer", T, RT_SCALARS) {
    std::mt19937 rng(20261104);
    std::uniform_real_distribution<double> coord(-10, 10), dir(-1, 1), exponent(-2, 2);
    int wrong_hit_or_miss = 0, wrong_t = 0, bad_record = 0, checked = 0;
    for (int i = 0; i < 5000; ++i) {
        const T nscale = T(std::pow(10.0, exponent(rng)));
        const plane<T> p{{T(coord(rng)), T(coord(rng)), T(coord(rng))},
                         {T(dir(rng)) * nscale, T(dir(rng)) * nscale, T(dir(rng)) * nscale}, 0};
        const ray<T> r{{T(coord(rng)), T(coord(rng)), T(coord(rng))}, {T(dir(rng)), T(dir(rng)), T(dir(rng))}};
        const interval<T> range{T(dir(rng)), T(std::fabs(coord(rng)) * 3)};
        long double t = 0, spread = 0;
        if (!reference_t(p, r, t, spread)) continue;
        // Skip cases too close to grazing or to an end of the range to judge.
        const long double margin = 64 * epsilon<T>() * spread;
        if (!(spread < 1e3L * (1 + std::fabs(t)))) continue;
        if (std::fabs(t - range.min) <= margin || std::fabs(t - range.max) <= margin) continue;
        const bool want_hit = t > range.min && t < range.max;
        ++checked;
        auto got = intersect_plane(p, r, range);
        if (got.has_value() != want_hit) { ++wrong_hit_or_miss; continue; }
        if (!got) continue;
        if (!(std::fabs((long double)got->t - t) <= margin)) ++wrong_t;
        if (!good_normal(*got, p) || !point_on_ray(*got, r)) ++bad_record;
    }
    CHECK(checked > 4000);
    CHECK_MESSAGE(wrong_hit_or_miss == 0, "random rays: some hits were reported as misses or misses as hits");
    CHECK_MESSAGE(wrong_t == 0, "random rays: some hits returned a t that is not the crossing of ray and plane");
    CHECK_MESSAGE(bad_record == 0, "random rays: some hit records had a wrong point or normal");
}

TEST_CASE_TEMPLATE("hidden: exactly parallel rays whose rounded d.n is not 0 keep the contract", T, RT_SCALARS) {
    // d.n = 0 exactly, but the rounded d.n is 2^-(2h+1) (h = digits / 2 + 1):
    // the header allows a far hit here (or, in the plane, a point of the
    // ray), never a NaN, an infinity or a t outside the range.
    const int h = std::numeric_limits<T>::digits / 2 + 1;
    const vec3<T> d(1 + std::ldexp(T(1), -h), 1 + std::ldexp(T(1), -h) + std::ldexp(T(1), -h - 1),
                    std::ldexp(T(1), -2 * h - 1));
    const vec3<T> n(-(1 + std::ldexp(T(1), -h - 1)), 1, 1);
    bool ok = dot(d, n) != T(0);  // the case is stiff
    // One unit off the plane: a crossing, if reported, is far beyond 1e6.
    auto off = intersect_plane(plane<T>{{0, 0, 1}, n, 0}, ray<T>{{0, 0, 0}, d}, ahead<T>());
    ok = ok && (!off || (std::isfinite(off->t) && off->t > T(1e6) && good_normal(*off, plane<T>{{0, 0, 1}, n, 0})));
    // A tmax of 1e6 (a scene's size) turns it into the miss it is.
    ok = ok && !intersect_plane(plane<T>{{0, 0, 1}, n, 0}, ray<T>{{0, 0, 0}, d}, interval<T>{0, T(1e6)});
    // In the plane (it passes through o + d): any reported t is in range and finite.
    auto in = intersect_plane(plane<T>{d, n, 0}, ray<T>{{0, 0, 0}, d}, interval<T>{0, T(10)});
    ok = ok && (!in || (std::isfinite(in->t) && in->t > 0 && in->t < T(10)));
    CHECK_MESSAGE(ok, "a ray whose rounded d.n is tiny but not 0 must still give a finite t inside the range (a far "
                      "crossing), never NaN or infinity");
}
