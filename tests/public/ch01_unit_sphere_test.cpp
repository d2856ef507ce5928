// Public tests for chapter 01: the unit sphere.
//
// Each case is one idea from the lecture. When a check fails, its message
// names that idea; the numbers follow.
#include "01-unit-sphere/unit_sphere.hpp"

#include "test_support.hpp"

#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>

using namespace rt;
using rt::ch01::intersect_unit_sphere;
using rt::test::close;
using rt::test::describe;
using rt::test::everything_ahead;

namespace {

// What a wrong t says about the code that produced it. The tests may run in
// any order (ctest starts the slow ones first), so every message names the
// mistake its own numbers point to, not the one its test was written for.
// `known` pairs a classic wrong answer with the lecture's name for it.
template <class T>
std::string diagnosis(const std::optional<T>& t, std::initializer_list<std::pair<double, const char*>> known) {
    if (t && std::isnan(*t))
        return ". A NaN is never a hit: it comes from sqrt of a negative discriminant (test "
               "'discriminant < 0' first and return std::nullopt) or from dividing by A = 0.";
    for (const auto& [value, mistake] : known)
        if (t && rt::test::close(*t, T(value))) return std::string(". ") + mistake;
    return "";
}

constexpr const char* far_root = "That is the far root (where the ray leaves the sphere): the ray sees the entry "
                                 "point first, the smaller root (-b - sqrt(disc)) / A.";

}  // namespace

TEST_CASE_TEMPLATE("a ray that passes beside the sphere misses it", T, RT_SCALARS) {
    // The ray runs parallel to z at height y = 2: it never comes closer than 2 to the origin.
    ray<T> r{{0, 2, 5}, {0, 0, -1}};
    auto t = intersect_unit_sphere(r, everything_ahead<T>());
    CHECK_MESSAGE(!t.has_value(),
                  "this ray never comes closer than 2 to the centre, so the quadratic has no real root "
                  "(negative discriminant) and the answer must be a miss; got "
                      << describe(t) << diagnosis(t, {}));
}

TEST_CASE_TEMPLATE("a ray through the centre hits the near side first", T, RT_SCALARS) {
    // From z = 5 towards the origin: the ray enters at z = 1 (t = 4) and leaves at z = -1 (t = 6).
    ray<T> r{{0, 0, 5}, {0, 0, -1}};
    auto t = intersect_unit_sphere(r, everything_ahead<T>());
    REQUIRE_MESSAGE(t.has_value(),
                    "the ray from (0,0,5) towards the origin crosses the sphere twice (positive discriminant), "
                    "but a miss was returned");
    CHECK_MESSAGE(close(*t, T(4)),
                  "the quadratic has two roots, t = 4 (entering) and t = 6 (leaving); the one we see is the "
                  "nearer root, t = 4. Got "
                      << describe(t) << diagnosis(t, {{6, far_root}}));
}

TEST_CASE_TEMPLATE("a tangent ray touches the sphere once", T, RT_SCALARS) {
    // At height y = 1 the ray grazes the top of the sphere at (0, 1, 0), t = 5:
    // the discriminant is exactly zero and both roots coincide.
    ray<T> r{{0, 1, 5}, {0, 0, -1}};
    auto t = intersect_unit_sphere(r, everything_ahead<T>());
    REQUIRE_MESSAGE(t.has_value(),
                    "a tangent ray has a discriminant of exactly zero: one (double) root, which is a hit. "
                    "Test 'discriminant < 0' for a miss, not 'discriminant <= 0'");
    CHECK_MESSAGE(close(*t, T(5)), "the tangent point (0,1,0) is at t = 5; got " << describe(t) << diagnosis(t, {}));
}

TEST_CASE_TEMPLATE("a sphere behind the ray is not hit", T, RT_SCALARS) {
    // The ray starts at z = 5 and points away from the sphere: both roots are negative.
    ray<T> r{{0, 0, 5}, {0, 0, 1}};
    auto t = intersect_unit_sphere(r, everything_ahead<T>());
    CHECK_MESSAGE(!t.has_value(),
                  "both roots are negative (t = -6 and t = -4): the sphere is behind the ray's origin. "
                  "Only t inside the interval (tmin, tmax) counts: check each root against tmin as well as "
                  "tmax; got "
                      << describe(t) << diagnosis(t, {}));
}

TEST_CASE_TEMPLATE("a ray starting inside the sphere hits the far root", T, RT_SCALARS) {
    // From the centre, going up: the roots are t = -1 (behind) and t = 1 (in front).
    ray<T> r{{0, 0, 0}, {0, 1, 0}};
    auto t = intersect_unit_sphere(r, everything_ahead<T>());
    REQUIRE_MESSAGE(t.has_value(),
                    "the ray starts inside the sphere, so it must cross the surface on its way out; got a miss. "
                    "The near root (t = -1) is behind the origin: when it is out of range, try the far root");
    CHECK_MESSAGE(close(*t, T(1)),
                  "the ray starts inside the sphere: the nearer root (t = -1) is behind it, so the hit in "
                  "front of the origin is the far root, t = 1. Got "
                      << describe(t)
                      << diagnosis(t, {{-1, "That root is behind the origin: check it against tmin before you "
                                            "return it."}}));
}

TEST_CASE_TEMPLATE("a non-unit direction scales t, not the hit point", T, RT_SCALARS) {
    // Same ray as 'through the centre' but with direction (0,0,-2): every t halves.
    ray<T> r{{0, 0, 5}, {0, 0, -2}};
    auto t = intersect_unit_sphere(r, everything_ahead<T>());
    REQUIRE_MESSAGE(t.has_value(), "the direction's length does not change which points the ray visits; got a miss");
    CHECK_MESSAGE(close(*t, T(2)),
                  "with direction (0,0,-2) the hit point (0,0,1) is reached at t = 2. Got "
                      << describe(t)
                      << diagnosis(t, {{3, far_root},
                                       {4, "That is the distance to the hit, not its t: normalising d changes t. "
                                           "Keep the caller's d and A = d . d in the quadratic."},
                                       {10 - std::sqrt(76.0), "Your formula assumes d . d = 1 (it drops A): keep "
                                                              "A = d . d in the quadratic."}}));
}

TEST_CASE_TEMPLATE("perspective rays only see what is beyond the image plane (t > 1)", T, RT_SCALARS) {
    // An eye at z = 1.5 with the image plane at distance 1 (z = 0.5): the sphere's
    // front at z = 1 is between the eye and the image plane, at t = 0.5.
    ray<T> r{{0, 0, T(1.5)}, {0, 0, -1}};
    auto t = intersect_unit_sphere(r, interval<T>::in_front_of_image_plane());
    REQUIRE_MESSAGE(t.has_value(),
                    "the ray leaves the sphere at t = 2.5, beyond the image plane, so it is a hit; got a miss. The "
                    "entry root (t = 0.5) is out of range: then the far root is the answer");
    CHECK_MESSAGE(close(*t, T(2.5)),
                  "for a perspective ray only t > 1 is in front of the image plane: the entry at t = 0.5 lies "
                  "between the eye and the image plane and must be skipped, leaving the exit at t = 2.5. Got "
                      << describe(t)
                      << diagnosis(t, {{0.5, "That is the entry root, at t < tmin = 1: check each root against the "
                                             "caller's tmin, and take the far root when the near one is out of "
                                             "range."}}));
}

TEST_CASE_TEMPLATE("a hit beyond tmax does not count", T, RT_SCALARS) {
    ray<T> r{{0, 0, 5}, {0, 0, -1}};
    auto t = intersect_unit_sphere(r, interval<T>{T(0), T(3)});
    CHECK_MESSAGE(!t.has_value(),
                  "both roots (t = 4 and t = 6) are beyond tmax = 3, so nothing in the interval is hit: check "
                  "each root against tmax as well as tmin; got "
                      << describe(t) << diagnosis(t, {}));
}

TEST_CASE_TEMPLATE("a hit exactly at tmin does not count (the range is open)", T, RT_SCALARS) {
    // The ray starts on the sphere's surface at (0,0,1) and goes through it:
    // the roots are exactly t = 0 (where it starts) and t = 2 (the far side).
    ray<T> r{{0, 0, 1}, {0, 0, -1}};
    auto t = intersect_unit_sphere(r, everything_ahead<T>());
    REQUIRE_MESSAGE(t.has_value(), "the ray crosses the sphere's far side at t = 2, inside (0, inf); got a miss. The "
                                   "near root (t = 0) is out of range: then the far root is the answer");
    CHECK_MESSAGE(close(*t, T(2)),
                  "the roots are t = 0 and t = 2, and the range is (0, inf), open at both ends: t = 0 is not "
                  "inside it (test tmin < t < tmax strictly, with range.surrounds(t), never t >= tmin), so the hit "
                  "is t = 2. Got "
                      << describe(t) << diagnosis(t, {{0, "t = tmin is on the boundary: the range is open."}}));
}
