// Public tests for chapter 07, step 6: the whole robust sphere test
// (steps 1 to 5 on their own are in ch07_steps_test.cpp).
//
// Two kinds of cases. The stiff ones come straight from the lecture: a unit
// sphere thousands of radii away, and a huge ground sphere seen from 1 unit
// above. They are where the plain formula of chapter 02 breaks in float, so
// they are checked in ULPs (how many representable numbers lie between your
// t and the true one). The others are chapter 02's contract again: the
// robust test must still be a correct sphere test.
//
// Every expected t below was worked out from the exact inputs with 60
// significant digits; every input is exactly representable in float.
#include "07-precision/robust_sphere.hpp"

#include "common/error_metrics.hpp"
#include "test_support.hpp"

#include <limits>

using namespace rt;
using rt::ch07::intersect_sphere_robust;
using rt::test::close;
using rt::test::describe;

namespace {

template <class T>
interval<T> ahead() {
    return {T(0), infinity<T>};
}

template <class T>
std::optional<T> t_of(const std::optional<hit_record<T>>& hit) {
    return hit ? std::optional<T>(hit->t) : std::nullopt;
}

// How many ULPs of T separate the returned t from the exact one (rounded to T).
template <class T>
double ulps_from(const std::optional<hit_record<T>>& hit, long double exact) {
    return hit ? ulp_distance(hit->t, static_cast<T>(exact)) : std::numeric_limits<double>::infinity();
}

// The lecture's huge ground: radius 1e6, top at y = 0, the ray starting 1 unit above it.
template <class T>
sphere<T> ground() {
    return {{T(0), T(-1e6), T(0)}, T(1e6)};
}

// What a wrong near root on a far unit sphere says about the formula. t at the
// centre's distance means sqrt(disc) came out 0: b^2 - ac cancelled away the
// radius, which is chapter 02's formula meeting trap 1.
template <class T>
std::string far_root_diagnosis(const std::optional<hit_record<T>>& hit, long double centre_distance) {
    if (hit && static_cast<long double>(hit->t) == centre_distance)
        return " (the distance to the centre itself: the discriminant came out 0, because b^2 - a c cancelled the "
               "radius away. That is chapter 02's formula meeting trap 1; compute the discriminant from the foot of "
               "the perpendicular, fix 1, step 1's quarter_discriminant)";
    return "";
}

}  // namespace

TEST_CASE_TEMPLATE("step6: a unit sphere 4100 radii away is hit through its middle and missed beside it", T, RT_SCALARS) {
    // An orthographic ray along -z from x = 0.75: the sphere's silhouette has radius 1.
    const sphere<T> s{{0, 0, T(-4100)}, T(1)};
    auto hit = intersect_sphere_robust(s, ray<T>{{T(0.75), 0, 0}, {0, 0, -1}}, ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "the ray passes 0.75 from the centre of a radius-1 sphere 4100 units away, so it must hit. In "
                    "float, c = f.f - r^2 = 16810000.5625 - 1 cannot even be stored (float's spacing there is 2): "
                    "compute the discriminant from the foot of the perpendicular instead, subtracting the vectors "
                    "before squaring");
    CHECK_MESSAGE(ulps_from(hit, 4099.338562172233852L) <= 2,
                  "the near root is t = 4099.338562172 (4100 - sqrt(1 - 0.75^2)); got " << describe(t_of(hit))
                                                                                   << far_root_diagnosis(hit, 4100));

    auto beside = intersect_sphere_robust(s, ray<T>{{T(1.01), 0, 0}, {0, 0, -1}}, ahead<T>());
    CHECK_MESSAGE(!beside.has_value(),
                  "this ray passes 1.01 radii from the centre, outside the sphere, so it must miss. A hit here "
                  "means the radius no longer counts: squaring |f| = 4100 halved float's useful bits, and "
                  "2^12 = 4096 radii is where r^2 falls below the rounding of f.f. Got "
                      << describe(t_of(beside)));
}

TEST_CASE_TEMPLATE("step6: a unit sphere 1e5 radii away is still hit and missed correctly", T, RT_SCALARS) {
    const sphere<T> s{{0, 0, T(-1e5)}, T(1)};
    auto hit = intersect_sphere_robust(s, ray<T>{{T(0.75), 0, 0}, {0, 0, -1}}, ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "a ray 0.75 from the centre of a unit sphere 1e5 units away must hit: with the foot of the "
                    "perpendicular, foot = f - (f.d / d.d) d = (0.75, 0, 0) exactly, and r^2 - foot.foot > 0");
    CHECK_MESSAGE(ulps_from(hit, 99999.33856217223385L) <= 2,
                  "the near root is t = 99999.338562172; got " << describe(t_of(hit)) << far_root_diagnosis(hit, 1e5L));
    auto beside = intersect_sphere_robust(s, ray<T>{{T(1.01), 0, 0}, {0, 0, -1}}, ahead<T>());
    CHECK_MESSAGE(!beside.has_value(), "a ray 1.01 radii from the centre misses, however far away the sphere is; got "
                                           << describe(t_of(beside)));
}

TEST_CASE_TEMPLATE("step6: a slanted ray from far away keeps the perpendicular distance", T, RT_SCALARS) {
    // From the origin, aimed 0.75 to the side of a unit sphere 4100 away: the
    // direction is not unit length and not along an axis.
    const sphere<T> s{{0, 0, T(-4100)}, T(1)};
    const T side = T(0.75) / T(4100);
    auto hit = intersect_sphere_robust(s, ray<T>{{0, 0, 0}, {side, 0, -1}}, ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "this ray passes about 0.75 from the centre and must hit; got a miss");
    const long double exact = 4099.3384249739546L;  // for side = 0.75 / 4100 (its rounding moves t by far less)
    CHECK_MESSAGE(std::fabs(static_cast<long double>(hit->t) - exact) <= 2e-3L,
                  "the near root is t = 4099.33842 (within float's spacing of 0.0005 there); the foot of the "
                  "perpendicular needs (f.d / d.d) d, with d.d, since d is not unit length. Got "
                      << describe(t_of(hit)));
}

TEST_CASE_TEMPLATE("step6: the huge ground sphere is hit accurately from 1 unit above", T, RT_SCALARS) {
    // Radius 1e6, the ray starts 1 above the top. Straight down the hit is at t = 1 exactly.
    const ray<T> down{{0, 1, 0}, {0, -1, 0}};
    auto hit = intersect_sphere_robust(ground<T>(), down, ahead<T>());
    CHECK_MESSAGE(ulps_from(hit, 1.0L) <= 2,
                  "straight down from 1 unit above, the ground is at t = 1. Here half_b = -(1e6 + 1) and "
                  "disc/4 = r^2 are exact, so even -half_b - sqrt(disc/4) gives exactly 1: a wrong t comes from "
                  "c = f.f - r^2, which cancels (f.f and r^2 agree in their first six digits; float keeps each to a "
                  "spacing of 65536). Keep the low halves of the squares (std::fma) and add them with a compensated "
                  "sum. Got "
                      << describe(t_of(hit)));

    // Slanted rays: down at 45 degrees, then shallower, then off to the side.
    struct aimed {
        T x, y, z;
        long double exact;
    };
    const aimed cases[] = {{0, -1, -1, 1.000000500000500001L},
                           {T(0.5), T(-0.25), -1, 4.000040000800020201L},
                           {0, T(-0.125), -1, 8.000256016385314934L}};
    for (const aimed& c : cases) {
        auto h = intersect_sphere_robust(ground<T>(), ray<T>{{0, 1, 0}, {c.x, c.y, c.z}}, ahead<T>());
        CHECK_MESSAGE(ulps_from(h, c.exact) <= 16,
                      "from 1 unit above the huge ground, along direction (" << c.x << ", " << c.y << ", " << c.z
                          << "), the exact hit is t = " << double(c.exact)
                          << ". Off by many ULPs means cancellation: in the near root -b - sqrt(disc) (use c / q), "
                             "or in c = f.f - r^2 itself, where f.f and r^2 agree in their first six digits "
                             "(keep the low halves of the squares with std::fma). Got "
                          << describe(t_of(h)) << ", " << ulps_from(h, c.exact) << " ULPs away");
    }
}

TEST_CASE_TEMPLATE("step6: rays touching a sphere are hits and rays just outside are misses", T, RT_SCALARS) {
    // Sphere of radius 1 at distance 5: a ray at height y = 1 touches its top.
    const sphere<T> s{{0, 0, -5}, T(1)};
    auto touching = intersect_sphere_robust(s, ray<T>{{0, 1, 0}, {0, 0, -1}}, ahead<T>());
    REQUIRE_MESSAGE(touching.has_value(), "a tangent ray has a zero discriminant: one double root, a hit");
    CHECK_MESSAGE(close(touching->t, T(5)), "the tangent point is at t = 5; got " << describe(t_of(touching)));

    const T eps = T(1) / T(1 << 20);  // 2^-20, exactly representable
    auto just_inside = intersect_sphere_robust(s, ray<T>{{0, 1 - eps, 0}, {0, 0, -1}}, ahead<T>());
    REQUIRE_MESSAGE(just_inside.has_value(), "a ray 2^-20 below the top of the sphere passes inside it: a hit");
    CHECK_MESSAGE(std::fabs(static_cast<long double>(just_inside->t) - 4.998618932397267318L) <= 1e-5L,
                  "2^-20 inside the top, the near root is t = 4.9986189 (5 - sqrt(1 - y^2)); got "
                      << describe(t_of(just_inside)));
    auto just_outside = intersect_sphere_robust(s, ray<T>{{0, 1 + eps, 0}, {0, 0, -1}}, ahead<T>());
    CHECK_MESSAGE(!just_outside.has_value(),
                  "a ray 2^-20 above the top of the sphere passes outside it: a miss; got " << describe(t_of(just_outside)));

    // The same grazing pair 4100 radii away: the plain formula cannot tell them apart in float.
    const sphere<T> far{{0, 0, T(-4100)}, T(1)};
    const T e10 = T(1) / T(1 << 10);
    auto far_inside = intersect_sphere_robust(far, ray<T>{{0, 1 - e10, 0}, {0, 0, -1}}, ahead<T>());
    auto far_outside = intersect_sphere_robust(far, ray<T>{{0, 1 + e10, 0}, {0, 0, -1}}, ahead<T>());
    CHECK_MESSAGE(far_inside.has_value(),
                  "a ray 2^-10 inside the top of a unit sphere 4100 away must hit: the perpendicular foot is "
                  "(0, 1 - 2^-10, 0), no rounding at all");
    CHECK_MESSAGE(!far_outside.has_value(),
                  "a ray 2^-10 outside the top of a unit sphere 4100 away must miss; got " << describe(t_of(far_outside)));
}

TEST_CASE_TEMPLATE("step6: a ray starting inside the sphere hits the far root", T, RT_SCALARS) {
    const sphere<T> s{{0, 0, -5}, T(2)};
    auto hit = intersect_sphere_robust(s, ray<T>{{0, 0, -5}, {0, 0, -1}}, ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "from the centre every ray leaves the sphere: a hit, got a miss");
    CHECK_MESSAGE(close(hit->t, T(2)),
                  "from the centre the roots are t = -2 (behind) and t = 2: the hit is the far root. With the stable "
                  "pair, c / q and q / a are not ordered by themselves; compare them. Got "
                      << describe(t_of(hit)));
    // From inside and moving so that half_b > 0: the far root is c / q this time.
    auto up = intersect_sphere_robust(s, ray<T>{{0, 0, -4}, {0, 0, 1}}, ahead<T>());
    REQUIRE_MESSAGE(up.has_value(), "from inside, going towards +z, the ray leaves the sphere at z = -3: a hit");
    CHECK_MESSAGE(close(up->t, T(1)), "leaving at z = -3 means t = 1; got " << describe(t_of(up)));
}

TEST_CASE_TEMPLATE("step6: an origin on the surface does not hit itself but crosses the sphere inwards", T, RT_SCALARS) {
    const sphere<T> s{{0, 0, 0}, T(1)};
    auto outwards = intersect_sphere_robust(s, ray<T>{{0, 0, 1}, {0, 0, 1}}, ahead<T>());
    CHECK_MESSAGE(!outwards.has_value(),
                  "leaving the surface the roots are t = -2 and t = 0, and t = 0 is not > tmin = 0; got "
                      << describe(t_of(outwards)));
    auto inwards = intersect_sphere_robust(s, ray<T>{{0, 0, 1}, {0, 0, -1}}, ahead<T>());
    REQUIRE_MESSAGE(inwards.has_value(), "going into the sphere from its surface, the ray reaches the far side");
    CHECK_MESSAGE(close(inwards->t, T(2)), "the far side is at t = 2; got " << describe(t_of(inwards)));
}

TEST_CASE_TEMPLATE("step6: the robust test keeps chapter 02's contract", T, RT_SCALARS) {
    const sphere<T> s{{0, 0, -4}, T(1)};
    const ray<T> r{{0, 0, 0}, {0, 0, -1}};  // roots t = 3 and t = 5

    CHECK_MESSAGE(!intersect_sphere_robust(s, ray<T>{{0, 2, 0}, {0, 0, -1}}, ahead<T>()).has_value(),
                  "a ray passing 2 from the centre of a radius-1 sphere misses");
    CHECK_MESSAGE(!intersect_sphere_robust(s, ray<T>{{0, 0, 0}, {0, 0, 1}}, ahead<T>()).has_value(),
                  "the sphere is behind this ray (roots t = -5 and t = -3): only tmin < t counts");

    auto near = intersect_sphere_robust(s, r, ahead<T>());
    REQUIRE_MESSAGE(near.has_value(), "the ray goes straight through the sphere; got a miss");
    CHECK_MESSAGE(close(near->t, T(3)), "the visible hit is the nearer root t = 3; got " << describe(t_of(near)));
    CHECK_MESSAGE(close(near->point.z, T(-3)), "point must be r.at(t) = (0, 0, -3); got " << describe(near->point));
    CHECK_MESSAGE((close(near->normal.z, T(1)) && close(length(near->normal), T(1))),
                  "the normal must be the outward unit normal (0, 0, 1); got " << describe(near->normal));
    CHECK_MESSAGE(near->object == -1, "object is left at -1 for the scene loop to fill in");

    CHECK_MESSAGE(!intersect_sphere_robust(s, r, interval<T>{0, T(2.5)}).has_value(),
                  "both roots (3 and 5) lie beyond tmax = 2.5: a miss");
    auto far = intersect_sphere_robust(s, r, interval<T>{T(3), T(10)});
    REQUIRE_MESSAGE(far.has_value(), "with tmin = 3 the far root t = 5 is still in range");
    CHECK_MESSAGE(close(far->t, T(5)),
                  "the interval is open: t = 3 is not > tmin = 3, so the hit is the far root t = 5; got "
                      << describe(t_of(far)));
    CHECK_MESSAGE(!intersect_sphere_robust(s, r, interval<T>{T(3), T(5)}).has_value(),
                  "with the open interval (3, 5) neither root counts");

    auto scaled = intersect_sphere_robust(s, ray<T>{{0, 0, 0}, {0, 0, -2}}, ahead<T>());
    REQUIRE_MESSAGE(scaled.has_value(), "the direction's length does not change which points the ray visits");
    CHECK_MESSAGE(close(scaled->t, T(1.5)),
                  "with direction (0, 0, -2) the hit (0, 0, -3) is at t = 1.5: keep a = d.d; got " << describe(t_of(scaled)));
}

TEST_CASE_TEMPLATE("step6: the smallest t in range is returned even when the sphere is behind", T, RT_SCALARS) {
    // With the whole line as the range, the roots t = -5 and t = -3 both count: the answer is -5.
    // Here half_b > 0, so q < 0 and q / a is the nearer root, c / q the farther.
    const sphere<T> s{{0, 0, -4}, T(1)};
    auto hit = intersect_sphere_robust(s, ray<T>{{0, 0, 0}, {0, 0, 1}}, interval<T>{-infinity<T>, infinity<T>});
    REQUIRE_MESSAGE(hit.has_value(), "with the range (-inf, inf) the sphere behind the ray is hit");
    CHECK_MESSAGE(close(hit->t, T(-5)),
                  "the smallest root is t = -5. The stable pair gives c / q and q / a, and which one is smaller "
                  "depends on the sign of b: when b > 0, c / q is the far root. Got "
                      << describe(t_of(hit)));
}

TEST_CASE_TEMPLATE("step6: the normal points outwards and has unit length on far and huge spheres", T, RT_SCALARS) {
    auto far = intersect_sphere_robust(sphere<T>{{0, 0, T(-4100)}, T(1)}, ray<T>{{T(0.75), 0, 0}, {0, 0, -1}},
                                       ahead<T>());
    REQUIRE_MESSAGE(far.has_value(), "the far sphere must be hit");
    CHECK_MESSAGE((std::fabs(length(far->normal) - T(1)) <= T(1e-5) && far->normal.z > T(0.6) &&
                   far->normal.x > T(0.7)),
                  "on the far sphere the outward unit normal is about (0.75, 0, 0.661); got " << describe(far->normal));
    auto huge = intersect_sphere_robust(ground<T>(), ray<T>{{0, 1, 0}, {T(0.5), T(-0.25), -1}}, ahead<T>());
    REQUIRE_MESSAGE(huge.has_value(), "the ground must be hit");
    CHECK_MESSAGE((std::fabs(length(huge->normal) - T(1)) <= T(1e-5) && huge->normal.y > T(0.999)),
                  "on the ground the outward normal points up, (0, 1, 0) to within 2e-6; got " << describe(huge->normal));
}

TEST_CASE_TEMPLATE("step6: bad input is a miss never a NaN", T, RT_SCALARS) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const sphere<T> s{{0, 0, -4}, T(1)};
    CHECK_MESSAGE(!intersect_sphere_robust(s, ray<T>{{0, 0, 0}, {0, 0, 0}}, ahead<T>()).has_value(),
                  "a zero direction is no ray: a miss");
    CHECK_MESSAGE(!intersect_sphere_robust(s, ray<T>{{nan, 0, 0}, {0, 0, -1}}, ahead<T>()).has_value(),
                  "a NaN origin: a miss (write tests as !(x >= 0) so NaN fails them)");
    CHECK_MESSAGE(!intersect_sphere_robust(sphere<T>{{0, 0, -4}, T(0)}, ray<T>{{0, 0, 0}, {0, 0, -1}}, ahead<T>())
                       .has_value(),
                  "a sphere of radius 0 is no sphere: a miss");
    CHECK_MESSAGE(!intersect_sphere_robust(sphere<T>{{0, 0, -4}, T(-1)}, ray<T>{{0, 0, 0}, {0, 0, -1}}, ahead<T>())
                       .has_value(),
                  "a negative radius is no sphere: a miss");
}

namespace {
// A power of two at the edge of T's range where squares under- or overflow
// (2^-100 ~ 7.9e-31 and 2^100 in float, 2^-664 ~ 1e-200 and 2^664 in double).
template <class T>
T extreme_scale(bool huge) {
    const int e = sizeof(T) == sizeof(float) ? 100 : 664;
    return std::ldexp(T(1), huge ? e : -e);
}
}  // namespace

TEST_CASE_TEMPLATE("step6: tiny and huge spheres are found by scaling with powers of two", T, RT_SCALARS) {
    // The lecture's 4-units-away unit sphere, shrunk or blown up by s: every
    // input is s times a small number, so the exact hits are s times the
    // unscaled ones. r^2 = s^2 under- or overflows T: without step 0
    // (scaling f and r by a power of two) these spheres vanish or fill the sky.
    for (bool huge : {false, true}) {
        const T s = extreme_scale<T>(huge);
        const sphere<T> sp{{0, 0, -4 * s}, s};
        auto centre = intersect_sphere_robust(sp, ray<T>{{0, 0, 0}, {0, 0, -1}}, ahead<T>());
        CHECK_MESSAGE(ulps_from(centre, 3.0L * static_cast<long double>(s)) <= 4,
                      "a sphere of radius " << double(s) << " at 4 radii: the hit is at t = 3 radii. r^2 = "
                                            << double(s) * double(s) << " in T; scale f and r by 2^k first. Got "
                                            << describe(t_of(centre)));
        auto side = intersect_sphere_robust(sp, ray<T>{{0, s / 2, 0}, {0, 0, -1}}, ahead<T>());
        CHECK_MESSAGE(ulps_from(side, (4.0L - std::sqrt(0.75L)) * static_cast<long double>(s)) <= 4,
                      "half a radius off the axis the hit is at t = (4 - sqrt(0.75)) radii; got " << describe(t_of(side)));
        auto beside = intersect_sphere_robust(sp, ray<T>{{0, s * T(1.0078125), 0}, {0, 0, -1}}, ahead<T>());
        CHECK_MESSAGE(!beside.has_value(), "a ray passing 1.0078125 radii from the centre misses; got "
                                               << describe(t_of(beside)));
        // A direction as small (or large) as the sphere: t = 3.
        auto slow = intersect_sphere_robust(sp, ray<T>{{0, 0, 0}, {0, 0, -s}}, ahead<T>());
        CHECK_MESSAGE(ulps_from(slow, 3.0L) <= 4, "with direction (0, 0, -" << double(s) << ") the hit is at t = 3; "
                                                  "a = d.d under- or overflows: scale d by its own power of two. Got "
                                                      << describe(t_of(slow)));
    }
}

TEST_CASE_TEMPLATE("step6: a subnormal direction is not a zero direction", T, RT_SCALARS) {
    // d = 2^(min_exponent - 20): below the smallest normal number, so d.d is
    // 0 in T, but the ray still moves. The sphere is small enough for t to fit.
    const T d = std::ldexp(T(1), std::numeric_limits<T>::min_exponent - 20);
    const T s = std::ldexp(T(1), std::numeric_limits<T>::min_exponent + 30);
    auto hit = intersect_sphere_robust(sphere<T>{{0, 0, -4 * s}, s}, ray<T>{{0, 0, 0}, {0, 0, -d}}, ahead<T>());
    CHECK_MESSAGE(ulps_from(hit, 3.0L * static_cast<long double>(s) / static_cast<long double>(d)) <= 4,
                  "the direction (0, 0, -" << double(d) << ") is tiny, not zero: the hit is at t = 3 * 2^50. A test "
                  "like a = d.d > 0 calls it zero because d.d underflows; test the components, and scale. Got "
                      << describe(t_of(hit)));
}

TEST_CASE_TEMPLATE("step6: an origin and a centre near the largest number: o - C must not overflow", T, RT_SCALARS) {
    // M is T's largest finite number. o = -M and C = +M are finite, but o - C = -2M is not; the near
    // root is t = M (exact, and a number of T). Quarter o, C and r before the two-sum (README, step 0).
    const T M = std::numeric_limits<T>::max();
    auto hit = intersect_sphere_robust(sphere<T>{{0, 0, M}, M}, ray<T>{{0, 0, -M}, {0, 0, 1}}, ahead<T>());
    CHECK_MESSAGE(ulps_from(hit, static_cast<long double>(M)) <= 4,
                  "the hit is at t = " << double(M) << " (the largest number of T); got " << describe(t_of(hit)));
}
