// Hidden tests for chapter 01 (run by the autograder only).
//
// Failure messages name the idea that went wrong but never the expected
// numbers: every check is a plain bool computed beforehand.
#include "01-unit-sphere/unit_sphere.hpp"

#include "test_support.hpp"

#include <cmath>
#include <limits>
#include <random>

using namespace rt;
using rt::ch01::intersect_unit_sphere;

namespace {

template <class T>
interval<T> ahead() {
    return {T(0), infinity<T>};
}

template <class T>
bool near_value(const std::optional<T>& got, long double want, long double rel) {
    return got && std::isfinite(*got) && std::fabs((long double)*got - want) <= rel * (1 + std::fabs(want));
}

// Both roots of |o + t d|^2 = 1 in long double, from the rounded inputs,
// with the cancellation-free root pair. Returns false when there is no real root.
template <class T>
bool reference_roots(const ray<T>& r, long double& t0, long double& t1, long double& disc_ratio) {
    long double ox = r.origin.x, oy = r.origin.y, oz = r.origin.z;
    long double dx = r.direction.x, dy = r.direction.y, dz = r.direction.z;
    long double a = dx * dx + dy * dy + dz * dz;
    long double hb = ox * dx + oy * dy + oz * dz;
    long double c = ox * ox + oy * oy + oz * oz - 1;
    long double disc = hb * hb - a * c;
    disc_ratio = disc / (hb * hb + std::fabs(a * c) + 1e-30L);
    if (disc < 0) return false;
    long double q = -(hb + std::copysign(std::sqrt(disc), hb));
    long double x0 = c / q, x1 = q / a;
    if (q == 0) x0 = x1 = 0;
    t0 = std::fmin(x0, x1);
    t1 = std::fmax(x0, x1);
    return true;
}

template <class T>
long double tolerance() {
    return sizeof(T) == 4 ? 2e-4L : 1e-10L;
}

}  // namespace

TEST_CASE_TEMPLATE("hidden: a ray beside the sphere misses", T, RT_SCALARS) {
    bool ok = !intersect_unit_sphere(ray<T>{{T(1.5), 0, 5}, {0, 0, -1}}, ahead<T>()).has_value() &&
              !intersect_unit_sphere(ray<T>{{0, T(-1.01), 5}, {0, 0, -1}}, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "a ray that passes farther than 1 from the centre has a negative discriminant: a miss");
}

TEST_CASE_TEMPLATE("hidden: the nearer root is the visible hit", T, RT_SCALARS) {
    bool ok = near_value(intersect_unit_sphere(ray<T>{{0, 0, 5}, {0, 0, -1}}, ahead<T>()), 4, tolerance<T>()) &&
              near_value(intersect_unit_sphere(ray<T>{{-3, 0, 0}, {1, 0, 0}}, ahead<T>()), 2, tolerance<T>()) &&
              near_value(intersect_unit_sphere(ray<T>{{0, T(0.6), -7}, {0, 0, 1}}, ahead<T>()), 6.2L, tolerance<T>());
    CHECK_MESSAGE(ok, "with two roots in range, the hit returned must be the smaller t (the entry point)");
}

TEST_CASE_TEMPLATE("hidden: tangent rays count as hits", T, RT_SCALARS) {
    bool ok = near_value(intersect_unit_sphere(ray<T>{{0, 1, 5}, {0, 0, -1}}, ahead<T>()), 5, tolerance<T>()) &&
              near_value(intersect_unit_sphere(ray<T>{{1, -4, 0}, {0, 1, 0}}, ahead<T>()), 4, tolerance<T>());
    CHECK_MESSAGE(ok, "a discriminant of exactly zero is one touching point: it is a hit, not a miss");
}

TEST_CASE_TEMPLATE("hidden: a sphere entirely behind the origin is not hit", T, RT_SCALARS) {
    bool ok = !intersect_unit_sphere(ray<T>{{0, 0, 5}, {0, 0, 1}}, ahead<T>()).has_value() &&
              !intersect_unit_sphere(ray<T>{{3, 3, 3}, {1, 1, 1}}, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "both roots negative means the sphere is behind the ray: only tmin < t counts");
}

TEST_CASE_TEMPLATE("hidden: from inside the sphere the far root is the hit", T, RT_SCALARS) {
    bool ok = near_value(intersect_unit_sphere(ray<T>{{0, 0, 0}, {0, 0, 1}}, ahead<T>()), 1, tolerance<T>()) &&
              near_value(intersect_unit_sphere(ray<T>{{T(0.5), 0, 0}, {1, 0, 0}}, ahead<T>()), 0.5L, tolerance<T>()) &&
              near_value(intersect_unit_sphere(ray<T>{{T(0.5), 0, 0}, {-1, 0, 0}}, ahead<T>()), 1.5L, tolerance<T>());
    CHECK_MESSAGE(ok, "from inside, the nearer root is behind the origin: the hit is the far root");
}

TEST_CASE_TEMPLATE("hidden: the direction need not be unit length", T, RT_SCALARS) {
    bool ok = near_value(intersect_unit_sphere(ray<T>{{0, 0, 5}, {0, 0, -4}}, ahead<T>()), 1, tolerance<T>()) &&
              near_value(intersect_unit_sphere(ray<T>{{0, 0, 5}, {0, 0, T(-0.5)}}, ahead<T>()), 8, tolerance<T>());
    CHECK_MESSAGE(ok, "t scales with the direction's length: keep A = d . d in the quadratic");
}

TEST_CASE_TEMPLATE("hidden: perspective rays skip hits before the image plane", T, RT_SCALARS) {
    auto front = interval<T>::in_front_of_image_plane();
    bool ok = near_value(intersect_unit_sphere(ray<T>{{0, 0, T(1.5)}, {0, 0, -1}}, front), 2.5L, tolerance<T>()) &&
              !intersect_unit_sphere(ray<T>{{0, 0, T(1.5)}, {0, 0, 1}}, front).has_value() &&
              near_value(intersect_unit_sphere(ray<T>{{0, 0, 3}, {0, 0, -1}}, front), 2, tolerance<T>());
    CHECK_MESSAGE(ok, "with the image plane at t = 1, a hit at t <= 1 is between the eye and the image: skip it");
}

TEST_CASE_TEMPLATE("hidden: hits beyond tmax are rejected", T, RT_SCALARS) {
    bool ok = !intersect_unit_sphere(ray<T>{{0, 0, 5}, {0, 0, -1}}, interval<T>{0, T(3.9)}).has_value() &&
              near_value(intersect_unit_sphere(ray<T>{{0, 0, 5}, {0, 0, -1}}, interval<T>{0, T(4.1)}), 4,
                         tolerance<T>());
    CHECK_MESSAGE(ok, "a hit counts only when tmin < t < tmax: hits past tmax are not in range");
}

TEST_CASE_TEMPLATE("hidden: the interval is open at both ends", T, RT_SCALARS) {
    // Exactly representable roots: from z = 5 along -z the roots are exactly 4 and 6.
    ray<T> r{{0, 0, 5}, {0, 0, -1}};
    bool ok = !intersect_unit_sphere(r, interval<T>{0, T(4)}).has_value() &&
              near_value(intersect_unit_sphere(r, interval<T>{T(4), T(10)}), 6, tolerance<T>()) &&
              !intersect_unit_sphere(r, interval<T>{T(4), T(6)}).has_value();
    CHECK_MESSAGE(ok, "the rule is strict, tmin < t < tmax: a root exactly at tmin or tmax does not count");
}

TEST_CASE_TEMPLATE("hidden: an origin on the surface does not hit itself", T, RT_SCALARS) {
    bool ok = !intersect_unit_sphere(ray<T>{{0, 0, 1}, {0, 0, 1}}, ahead<T>()).has_value() &&
              near_value(intersect_unit_sphere(ray<T>{{0, 0, 1}, {0, 0, -1}}, ahead<T>()), 2, tolerance<T>());
    CHECK_MESSAGE(ok, "a ray leaving the surface has the root t = 0, which is not > tmin = 0; going inward it "
                      "hits the far side");
}

TEST_CASE_TEMPLATE("hidden: invalid rays are misses, never NaN", T, RT_SCALARS) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    bool ok = !intersect_unit_sphere(ray<T>{{0, 0, 5}, {0, 0, 0}}, ahead<T>()).has_value() &&
              !intersect_unit_sphere(ray<T>{{nan, 0, 5}, {0, 0, -1}}, ahead<T>()).has_value() &&
              !intersect_unit_sphere(ray<T>{{0, 0, 5}, {0, nan, -1}}, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "a zero direction or a NaN coordinate has no meaningful hit: return a miss, not NaN");
}

TEST_CASE_TEMPLATE("hidden: random rays agree with a higher-precision answer", T, RT_SCALARS) {
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> coord(-4, 4), dir(-1, 1), scale(0.1, 10);
    int wrong_hit_or_miss = 0, wrong_t = 0, checked = 0;
    for (int i = 0; i < 4000; ++i) {
        ray<T> r{{T(coord(rng)), T(coord(rng)), T(coord(rng))}, {T(dir(rng)), T(dir(rng)), T(dir(rng))}};
        r.direction *= T(scale(rng));
        if (!(dot(r.direction, r.direction) > T(1e-6))) continue;
        long double t0 = 0, t1 = 0, ratio = 0;
        bool real = reference_roots(r, t0, t1, ratio);
        if (std::fabs(ratio) < 1e-3L) continue;  // too close to tangent to judge hit or miss
        std::optional<long double> want;
        if (real && t0 > 0) want = t0;
        else if (real && t1 > 0) want = t1;
        if (want && *want < 1e-3L) continue;  // a root at the origin: too close to tmin to judge
        ++checked;
        auto got = intersect_unit_sphere(r, ahead<T>());
        if (got.has_value() != want.has_value()) ++wrong_hit_or_miss;
        else if (got && !near_value(got, *want, 100 * tolerance<T>())) ++wrong_t;
    }
    CHECK(checked > 3000);
    CHECK_MESSAGE(wrong_hit_or_miss == 0, "random rays: some hits were reported as misses or misses as hits");
    CHECK_MESSAGE(wrong_t == 0, "random rays: some hits returned the wrong t (which root? the right range?)");
}
