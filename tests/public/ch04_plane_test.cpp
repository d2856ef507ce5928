// Public tests for chapter 04: a ray against a plane.
//
// Each case is one idea from the lecture. When a check fails, its message
// names that idea; the numbers follow.
#include "04-plane/plane.hpp"

#include "test_support.hpp"

#include <cmath>

using namespace rt;
using rt::ch04::intersect_plane;
using rt::test::close;
using rt::test::describe;
using rt::test::describe_hit;
using rt::test::everything_ahead;
using rt::test::is_unit;

namespace {

// The ground: the plane y = 0 with its normal pointing up.
template <class T>
plane<T> ground() {
    return {{0, 0, 0}, {0, 1, 0}, 0};
}


}  // namespace

TEST_CASE_TEMPLATE("a ray straight down onto the ground hits it", T, RT_SCALARS) {
    // From height 3 straight down: t = (p0 - o).n / (d.n) = (0 - 3) / (-1) = 3.
    ray<T> r{{1, 3, 2}, {0, -1, 0}};
    auto hit = intersect_plane(ground<T>(), r, everything_ahead<T>());
    // A miss here is most often a sign error: ask again with the whole line as the range, and ask a ray
    // from below too (d . n > 0): a flipped numerator flips both, |d . n| only this one.
    const interval<T> whole_line{-infinity<T>, infinity<T>};
    auto anywhere = intersect_plane(ground<T>(), r, whole_line);
    auto from_below = intersect_plane(ground<T>(), ray<T>{{1, -2, 2}, {0, 1, 0}}, whole_line);
    const bool flipped = anywhere && close(anywhere->t, T(-3));
    const bool below_right = from_below && close(from_below->t, T(2));
    CHECK_MESSAGE(!(flipped && below_right),
                  "t came out as -3 for this ray from above (d . n = -1), but right (t = 2) for a ray from below "
                  "(d . n = +1): the denominator lost its sign. t = (p0 - o) . n / (d . n) needs d . n with its "
                  "sign; dividing by |d . n| (std::abs) flips t whenever the ray travels against the normal");
    CHECK_MESSAGE(!(flipped && !below_right),
                  "t came out as -3: the sign is flipped. The numerator is (p0 - o) . n, from the ray's origin to "
                  "the plane, not (o - p0) . n; with it a plane ahead of the ray gets a positive t");
    REQUIRE_MESSAGE(hit.has_value(), "a ray pointing straight at the plane must hit it; got a miss");
    CHECK_MESSAGE(close(hit->t, T(3)),
                  "t = (p0 - o) . n / (d . n) = (0 - 3) / (-1) = 3 for a ray from height 3 going straight "
                  "down; got "
                      << describe_hit(hit));
    CHECK_MESSAGE((close(hit->point.x, T(1)) && close(hit->point.y, T(0), T(1)) && close(hit->point.z, T(2))),
                  "the hit point is r(t) = o + t d, which lies on the plane below the origin, (1, 0, 2); got "
                      << describe_hit(hit));
    CHECK_MESSAGE((is_unit(hit->normal) && close(hit->normal.y, T(1))),
                  "the hit's normal is the plane's own normal at unit length, (0, 1, 0); got "
                      << describe_hit(hit));
}

TEST_CASE_TEMPLATE("an oblique ray hits the plane where the formula says", T, RT_SCALARS) {
    // From (0, 2, 0) along (1, -1, 0.5): d.n = -1, so t = 2 and the hit is (2, 0, 1).
    ray<T> r{{0, 2, 0}, {1, -1, T(0.5)}};
    auto hit = intersect_plane(ground<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "a ray going down towards the ground at an angle must hit it; got a miss");
    CHECK_MESSAGE(close(hit->t, T(2)),
                  "d . n = -1 and (p0 - o) . n = -2, so t = 2 (the direction is not unit length: t counts "
                  "steps of d, not distance); got "
                      << describe_hit(hit));
    CHECK_MESSAGE((close(hit->point.x, T(2)) && close(hit->point.y, T(0), T(1)) && close(hit->point.z, T(1))),
                  "the hit point r(2) = (2, 0, 1); got " << describe_hit(hit));
}

TEST_CASE_TEMPLATE("a ray parallel to the plane misses without NaN", T, RT_SCALARS) {
    // Height 1, moving sideways: d.n = 0, and (p0 - o).n = -1, so the formula would give -1/0.
    ray<T> r{{0, 1, 0}, {1, 0, -1}};
    auto hit = intersect_plane(ground<T>(), r, everything_ahead<T>());
    CHECK_MESSAGE(!hit.has_value(),
                  "a ray parallel to the plane (d . n = 0) never reaches it: it is a miss. Dividing by d . n "
                  "= 0 gives an infinity, which must not be returned as a hit; got "
                      << describe_hit(hit));
}

TEST_CASE_TEMPLATE("a ray lying in the plane is a miss", T, RT_SCALARS) {
    // In the plane and along it: d.n = 0 and (p0 - o).n = 0, so the formula is 0/0 = NaN.
    ray<T> r{{-1, 0, 3}, {1, 0, 0}};
    auto hit = intersect_plane(ground<T>(), r, everything_ahead<T>());
    CHECK_MESSAGE(!hit.has_value(),
                  "a ray lying in the plane touches it everywhere, so there is no single crossing: the "
                  "contract calls it a miss. The formula gives 0 / 0 = NaN here; test d . n before "
                  "dividing. Got "
                      << describe_hit(hit));
}

TEST_CASE_TEMPLATE("a plane hit from behind keeps its normal and shows its back face", T, RT_SCALARS) {
    // From below the ground, looking up: the plane's normal (0, 1, 0) points away from the ray.
    // The hit still reports (0, 1, 0); the one face rule (common/hit_record.hpp) says the ray
    // sees the back face and gives the normal on the ray's side, (0, -1, 0), for shading.
    ray<T> r{{0, -2, 0}, {0, 1, 0}};
    auto hit = intersect_plane(ground<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "a plane has two sides and can be hit from either: d . n > 0 is a hit from behind, not a "
                    "miss; got a miss");
    CHECK_MESSAGE(close(hit->t, T(2)), "from y = -2 going up, the plane y = 0 is reached at t = 2; got "
                                           << describe_hit(hit));
    CHECK_MESSAGE((is_unit(hit->normal) && close(hit->normal.y, T(1))),
                  "the normal is the plane's own, (0, 1, 0), from either side: do not turn it towards the ray "
                  "(hit.facing_normal(r) does that, once, for every shape). Got "
                      << describe_hit(hit));
    CHECK_MESSAGE(!hit->front_face(r), "a ray from below the ground sees its back face: front_face(r) is false");
    CHECK_MESSAGE(close(hit->facing_normal(r).y, T(-1)),
                  "seen from below, the normal on the ray's side is (0, -1, 0); got " << describe_hit(hit));
}

TEST_CASE_TEMPLATE("a plane behind the ray origin is not hit", T, RT_SCALARS) {
    // From height 2 going up: the plane y = 0 is behind, at t = -2.
    ray<T> r{{0, 2, 0}, {0, 1, 0}};
    auto hit = intersect_plane(ground<T>(), r, everything_ahead<T>());
    CHECK_MESSAGE(!hit.has_value(),
                  "the formula gives t = -2: the plane is behind the ray's origin. Only tmin < t < tmax "
                  "counts; got "
                      << describe_hit(hit));
}

TEST_CASE_TEMPLATE("hits outside (tmin tmax) do not count", T, RT_SCALARS) {
    ray<T> r{{0, 3, 0}, {0, -1, 0}};  // reaches the ground at t = 3
    auto too_far = intersect_plane(ground<T>(), r, interval<T>{T(0), T(2)});
    CHECK_MESSAGE(!too_far.has_value(), "the crossing at t = 3 is beyond tmax = 2; got " << describe_hit(too_far));
    auto too_near = intersect_plane(ground<T>(), r, interval<T>{T(4), T(10)});
    CHECK_MESSAGE(!too_near.has_value(),
                  "the crossing at t = 3 is before tmin = 4; got " << describe_hit(too_near));
    auto at_tmax = intersect_plane(ground<T>(), r, interval<T>{T(0), T(3)});
    CHECK_MESSAGE(!at_tmax.has_value(),
                  "the interval is open: t = 3 with tmax = 3 is not inside (tmin < t < tmax); got "
                      << describe_hit(at_tmax));
    auto inside = intersect_plane(ground<T>(), r, interval<T>{T(1), T(5)});
    CHECK_MESSAGE((inside.has_value() && close(inside->t, T(3))),
                  "t = 3 lies inside (1, 5), so it is a hit; got " << describe_hit(inside));
}

TEST_CASE_TEMPLATE("a non-unit plane normal gives the same hit and a unit normal", T, RT_SCALARS) {
    // The plane z = -4 written with normal (0, 0, 5): the length of n cancels out of t.
    plane<T> wall{{7, -3, -4}, {0, 0, 5}, 0};
    ray<T> r{{0, 0, 0}, {0, 0, -1}};
    auto hit = intersect_plane(wall, r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "the ray goes straight at the wall z = -4; got a miss");
    CHECK_MESSAGE(close(hit->t, T(4)),
                  "n appears above and below the fraction, so its length cancels: t = 4 whatever |n| is; got "
                      << describe_hit(hit));
    CHECK_MESSAGE(is_unit(hit->normal),
                  "the hit record's normal must be unit length even when the plane's normal is not: "
                  "normalise it. Got "
                      << describe_hit(hit));
    CHECK_MESSAGE(close(hit->normal.z, T(1)), "the plane's normal (0, 0, 5) at unit length is (0, 0, 1); got "
                                                  << describe_hit(hit));
}

TEST_CASE_TEMPLATE("a ray that skims the plane is not parallel", T, RT_SCALARS) {
    // d.n = -0.001: nearly parallel, and a real crossing at t = 1000 (the floor near the horizon).
    ray<T> r{{0, 1, 0}, {1, T(-0.001), 0}};
    auto hit = intersect_plane(ground<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "d . n = -0.001 is small, not zero: the ray reaches the ground at t = 1000. A test "
                                     "like |d . n| < 0.01 (an epsilon for 'parallel') throws away the far floor; only "
                                     "d . n == 0 is parallel. Got a miss");
    CHECK_MESSAGE(std::fabs(hit->t - T(1000)) <= T(1000) * T(1e-4), "the crossing is at t = 1000; got " << describe_hit(hit));
}

TEST_CASE_TEMPLATE("a plane normal of extreme length is normalised without overflow", T, RT_SCALARS) {
    // n.n overflows (1e30 in float, 1e200 in double) or underflows (1e-30, 1e-200) T.
    const T huge = sizeof(T) == 4 ? T(1e30) : T(1e200);
    const T tiny = sizeof(T) == 4 ? T(1e-30) : T(1e-200);
    ray<T> r{{1, 2, 3}, {0, -1, 0}};
    for (T len : {huge, tiny}) {
        auto hit = intersect_plane(plane<T>{{0, 0, 0}, {0, len, 0}, 0}, r, everything_ahead<T>());
        REQUIRE_MESSAGE(hit.has_value(), "the plane y = 0 with normal (0, " << len << ", 0) is the ground: a hit at "
                                                                              "t = 2; got a miss (n . n under- or "
                                                                              "overflowed?)");
        CHECK_MESSAGE(close(hit->t, T(2)), "t = 2 whatever the normal's length; got " << describe_hit(hit));
        CHECK_MESSAGE((is_unit(hit->normal) && close(hit->normal.y, T(1))),
                      "normal (0, " << len << ", 0): n . n = " << len * len << " in T, so n / length(n) breaks. Divide "
                      "by the largest component first, then by the length; expected (0, 1, 0), got "
                                    << describe_hit(hit));
    }
}
