// Public tests for chapter 02: a sphere with any centre and radius.
//
// Each case is one idea from the lecture. When a check fails, its message
// names that idea; the numbers follow.
#include "02-sphere/sphere.hpp"

#include "test_support.hpp"

#include <cmath>
#include <optional>
#include <string>

using namespace rt;
using rt::ch02::intersect_sphere;
using rt::test::close;
using rt::test::describe;
using rt::test::describe_hit;
using rt::test::everything_ahead;

namespace {

// A sphere of radius 2 centred at (1, 2, -3): away from the origin, not unit
// size, so a formula that forgets the centre or the radius shows it.
template <class T>
sphere<T> off_centre_sphere() {
    return {{T(1), T(2), T(-3)}, T(2)};
}

// What wrong numbers point to. ctest may run the tests in any order, so a
// failing check must not blame the idea its test was written for when the
// answer points elsewhere: these probes ask intersect_sphere easy questions,
// each sensitive to one classic mistake, and name the first one that shows.
template <class T>
std::string diagnosis() {
    const auto t_of = [](const sphere<T>& s, const ray<T>& r) {
        const auto hit = intersect_sphere(s, r, everything_ahead<T>());
        return hit ? hit->t : T(-1);
    };
    // The unit sphere at the origin, from z = 5: the roots are 4 and 6.
    const T plain = t_of({{0, 0, 0}, T(1)}, {{0, 0, 5}, {0, 0, -1}});
    if (close(plain, T(6)))
        return " [Your function returns the far root (where the ray leaves): the ray sees the near root, "
               "(-h - sqrt(disc)) / a, first.]";
    if (std::isnan(plain)) return " [A NaN t is never a hit: test the discriminant and the range first.]";
    if (close(plain, T(4))) {
        // The same ray and sphere moved by (10, 0, 0): nothing may change.
        if (!close(t_of({{10, 0, 0}, T(1)}, {{10, 0, 5}, {0, 0, -1}}), T(4)))
            return " [Moving ray and sphere together changes your answer: the centre is missing from the "
                   "quadratic. Use oc = o - C in place of o.]";
        // Radius 2 at the origin: the near root is 3.
        const T wide = t_of({{0, 0, 0}, T(2)}, {{0, 0, 5}, {0, 0, -1}});
        if (!close(wide, T(3)))
            return " [A sphere of radius 2 is hit as if its radius were " +
                   std::string(close(wide, T(4)) ? "1" : "wrong") + ": c = oc . oc - R^2 (R squared).]";
        // Direction (0,0,-2): a = d . d = 4, the near root is t = 2.
        const T doubled = t_of({{0, 0, 0}, T(1)}, {{0, 0, 5}, {0, 0, -2}});
        if (close(doubled, T(8)))
            return " [With direction (0,0,-2), a = d . d = 4, your t is 8, a times the right t = 2: the roots are "
                   "(-h -+ sqrt(h^2 - a c)) / a, divided by a.]";
        if (!close(doubled, T(2)))
            return " [With direction (0,0,-2) the hit must come at t = 2: keep a = d . d in the quadratic, do "
                   "not assume a unit direction.]";
    }
    return "";
}

}  // namespace

TEST_CASE_TEMPLATE("a ray that passes beside the sphere misses it", T, RT_SCALARS) {
    // Parallel to z at x = 1, y = 5: its closest approach to the centre (1,2,-3) is 3 > radius 2.
    ray<T> r{{1, 5, 5}, {0, 0, -1}};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    CHECK_MESSAGE(!hit.has_value(),
                  "this ray passes 3 units from the centre of a sphere of radius 2: the discriminant is negative, "
                  "there is no real root, and the answer must be a miss; got "
                      << describe_hit(hit) << diagnosis<T>());
}

TEST_CASE_TEMPLATE("a ray through the centre hits the near side first", T, RT_SCALARS) {
    // From z = 5 straight at the centre (1,2,-3): enters at z = -1 (t = 6), leaves at z = -5 (t = 10).
    ray<T> r{{1, 2, 5}, {0, 0, -1}};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "the ray aims straight at the centre, so it must cross the sphere (positive discriminant); "
                    "got a miss"
                        << diagnosis<T>());
    CHECK_MESSAGE(close(hit->t, T(6)),
                  "the roots are t = 6 (entering) and t = 10 (leaving); the surface we see is the nearer root, "
                  "t = 6. Got "
                      << describe_hit(hit) << diagnosis<T>());
}

TEST_CASE_TEMPLATE("a tangent ray touches the sphere once", T, RT_SCALARS) {
    // At x = 3 = centre.x + radius the ray grazes the sphere at (3, 2, -3), t = 8.
    ray<T> r{{3, 2, 5}, {0, 0, -1}};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "the ray at x = 3 grazes the sphere of radius 2 centred at x = 1; got a miss"
                        << (diagnosis<T>().empty() ? std::string(". A tangent ray has a discriminant of exactly zero: "
                                                                 "one (double) root, which is a hit. Test "
                                                                 "'discriminant < 0' for a miss, not "
                                                                 "'discriminant <= 0'")
                                                   : diagnosis<T>()));
    CHECK_MESSAGE(close(hit->t, T(8)), "the tangent point (3,2,-3) is at t = 8; got " << describe_hit(hit) << diagnosis<T>());
}

TEST_CASE_TEMPLATE("a sphere behind the ray is not hit", T, RT_SCALARS) {
    // The ray starts at z = 5 and points away: both roots (t = -10 and t = -6) are negative.
    ray<T> r{{1, 2, 5}, {0, 0, 1}};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    CHECK_MESSAGE(!hit.has_value(),
                  "both roots are negative (t = -10 and t = -6): the sphere is behind the ray's origin, and a "
                  "sphere behind the camera must not show up. Only t inside (tmin, tmax) counts; got "
                      << describe_hit(hit) << diagnosis<T>());
}

TEST_CASE_TEMPLATE("a ray starting inside the sphere hits the far root", T, RT_SCALARS) {
    // From the centre, going up: the roots are t = -2 (behind) and t = 2 (in front).
    ray<T> r{{1, 2, -3}, {0, 1, 0}};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "the ray starts inside the sphere, so it must cross the surface on its way out; got a miss"
                        << (diagnosis<T>().empty() ? std::string(". The near root is behind the origin: when it is "
                                                                 "out of range, try the far root")
                                                   : diagnosis<T>()));
    CHECK_MESSAGE(close(hit->t, T(2)),
                  "the ray starts inside the sphere: the nearer root (t = -2) is behind it, so the hit in front "
                  "of the origin is the far root, t = 2. Got "
                      << describe_hit(hit) << diagnosis<T>());
    CHECK_MESSAGE(close(hit->normal.y, T(1)),
                  "from inside too the normal points out of the sphere, (P - C) / R = (0, 1, 0); got "
                      << describe_hit(hit));
    // Which side the ray is on is the one face rule's answer (common/hit_record.hpp), not the exercise's.
    CHECK_MESSAGE(!hit->front_face(r), "a ray from inside meets the sphere's back face: front_face(r) is false");
    CHECK_MESSAGE(close(hit->facing_normal(r).y, T(-1)),
                  "seen from inside, the normal on the ray's side points to the centre, (0, -1, 0); got "
                      << describe_hit(hit));
}

TEST_CASE_TEMPLATE("a non-unit direction scales t but not the hit point", T, RT_SCALARS) {
    // Same ray as 'through the centre' but with direction (0,0,-4): every t is divided by 4.
    ray<T> r{{1, 2, 5}, {0, 0, -4}};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "the direction's length does not change which points the ray visits; got a miss" << diagnosis<T>());
    CHECK_MESSAGE(close(hit->t, T(1.5)),
                  "with direction (0,0,-4) the hit point (1,2,-1) is reached at t = 1.5 (the direction is not "
                  "unit length here: a = d . d = 16 stays in the quadratic and divides its roots). Got "
                      << describe_hit(hit) << diagnosis<T>());
    CHECK_MESSAGE(close(hit->point, vec3<T>(1, 2, -1)),
                  "whatever the direction's length, the ray meets the sphere at (1,2,-1); got " << describe_hit(hit) << diagnosis<T>());
}

TEST_CASE_TEMPLATE("the centre and radius are part of the equation", T, RT_SCALARS) {
    // A diagonal ray at the off-centre sphere: it aims at the centre from (1,2,-3) + 6 * (2,1,2)/3,
    // so it enters at distance 6 - 2 = 4 along the unit direction.
    const vec3<T> d = vec3<T>(-2, -1, -2) / T(3);
    ray<T> r{vec3<T>(1, 2, -3) - T(6) * d, d};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "the ray aims at the centre (1,2,-3) of a sphere of radius 2; got a miss. Did you use "
                    "o - C (origin minus centre) in the quadratic, and R^2 rather than 1?"
                        << diagnosis<T>());
    CHECK_MESSAGE(close(hit->t, T(4)),
                  "the origin is 6 from the centre along a unit direction, so the ray enters at t = 6 - R = 4. Got "
                      << describe_hit(hit) << diagnosis<T>());
}

TEST_CASE_TEMPLATE("the normal is the outward unit vector (P - C) / r", T, RT_SCALARS) {
    const vec3<T> d = normalize(vec3<T>(-1, -1, -3));
    ray<T> r{vec3<T>(2, 3, 4), d};
    const sphere<T> s = off_centre_sphere<T>();
    auto hit = intersect_sphere(s, r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "this ray crosses the sphere; got a miss" << diagnosis<T>());
    const vec3<T> expected = (hit->point - s.center) / s.radius;
    CHECK_MESSAGE(close(length(hit->normal), T(1)),
                  "the normal must be a unit vector: (P - C) has length R, so divide it by the radius. Its "
                  "length is "
                      << length(hit->normal) << " in " << describe_hit(hit) << diagnosis<T>());
    CHECK_MESSAGE(dot(hit->normal, expected) > T(0),
                  "the normal must point outwards, from the centre towards the hit point: (P - C), not (C - P). "
                  "Got "
                      << describe_hit(hit) << diagnosis<T>());
    CHECK_MESSAGE(close(hit->normal, expected),
                  "the normal at P is (P - C) / R = " << rt::test::describe(expected) << "; got " << describe_hit(hit) << diagnosis<T>());
}

TEST_CASE_TEMPLATE("the hit point is the ray at t", T, RT_SCALARS) {
    const vec3<T> d = vec3<T>(T(-0.5), T(-1), T(-2));
    ray<T> r{vec3<T>(2, 4, 2), d};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "this ray crosses the sphere; got a miss" << diagnosis<T>());
    CHECK_MESSAGE(close(hit->point, r.at(hit->t)),
                  "the hit point must be r(t) = o + t d for the t you return: expected "
                      << rt::test::describe(r.at(hit->t)) << ", got " << describe_hit(hit) << diagnosis<T>());
    CHECK_MESSAGE(close(length(hit->point - off_centre_sphere<T>().center), T(2)),
                  "the hit point must lie on the sphere, at distance R = 2 from the centre; got " << describe_hit(hit) << diagnosis<T>());
    CHECK_MESSAGE(hit->object == -1,
                  "intersect_sphere leaves the object index at -1: the scene loop of chapter 03 fills it in; got "
                      << hit->object);
}

TEST_CASE_TEMPLATE("only hits inside the interval tmin < t < tmax count", T, RT_SCALARS) {
    // Roots t = 6 and t = 10 (see 'through the centre').
    ray<T> r{{1, 2, 5}, {0, 0, -1}};
    const sphere<T> s = off_centre_sphere<T>();
    auto before = intersect_sphere(s, r, interval<T>{T(0), T(5)});
    CHECK_MESSAGE(!before.has_value(),
                  "both roots (t = 6 and t = 10) are beyond tmax = 5, so nothing in the interval is hit; got "
                      << describe_hit(before) << diagnosis<T>());
    auto skip_near = intersect_sphere(s, r, interval<T>{T(7), infinity<T>});
    REQUIRE_MESSAGE(skip_near.has_value(),
                    "with tmin = 7 the near root t = 6 is out, but the far root t = 10 is inside (7, inf); got "
                    "a miss"
                        << (diagnosis<T>().empty() ? std::string(": when the near root is out of range, try the far "
                                                                 "root")
                                                   : diagnosis<T>()));
    CHECK_MESSAGE(close(skip_near->t, T(10)),
                  "with tmin = 7 the near root t = 6 does not count, so the answer is the far root t = 10; got "
                      << describe_hit(skip_near) << diagnosis<T>());
    auto between = intersect_sphere(s, r, interval<T>{T(6.5), T(9.5)});
    CHECK_MESSAGE(!between.has_value(),
                  "in (6.5, 9.5) neither root (t = 6, t = 10) lies inside the interval, so it is a miss; got "
                      << describe_hit(between) << diagnosis<T>());
}

TEST_CASE_TEMPLATE("a root exactly at tmin does not count (the range is open)", T, RT_SCALARS) {
    // The ray starts on the surface at (1,2,-1) and goes through the sphere:
    // the roots are exactly t = 0 (where it starts) and t = 4 (the far side).
    ray<T> r{{1, 2, -1}, {0, 0, -1}};
    auto hit = intersect_sphere(off_centre_sphere<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(),
                    "the ray crosses the far side of the sphere at t = 4, inside (0, inf); got a miss"
                        << (diagnosis<T>().empty() ? std::string(": when the near root (t = 0) is out of range, try "
                                                                 "the far root")
                                                   : diagnosis<T>()));
    CHECK_MESSAGE(close(hit->t, T(4)),
                  "the roots are t = 0 and t = 4, and the range (0, inf) is open: t = 0 is not inside it (test "
                  "tmin < t < tmax strictly, with range.surrounds(t), never t >= tmin), so the hit is t = 4. Got "
                      << describe_hit(hit) << diagnosis<T>());
}
