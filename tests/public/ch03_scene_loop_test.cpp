// Public tests for chapter 03: the closest hit among many objects.
//
// The objects here are not spheres but the simplest thing a ray can hit: a
// "wall" that the ray crosses at one known parameter t (if that t is inside
// the range it is asked about). That way these tests check your loop alone,
// whatever the state of your chapter 02.
#include "03-scene-loop/scene_loop.hpp"

#include "rpc/served.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

using namespace rt;
using rt::ch03::closest_hit;
using rt::test::close;

namespace {

// Object i is met at t = walls[i]. Its hit record carries a normal that
// tells the walls apart: (i, 0, 0) + (0, 0, 1), so we can check that the
// loop hands back the record of the object it says it hit.
//
// The callback is a served one (tests/support/rpc/served.hpp): under the
// grader, each call your loop makes is answered by the grader's own process,
// with the same walls. The test's rules for the calls go with it:
// `budget` limits how many calls there may be, `expected` lists the calls
// in the order they must come. The grader keeps a record of the calls; when
// one breaks a rule, closest_hit fails with rt::test::broken_rule (saying
// which call, and what it asked), whatever it returns.
template <class T>
rt::test::served_objects<T> walls_at(const std::vector<T>& walls) {
    rt::test::served_objects<T> served;
    served.count = int(walls.size());
    served.test = [walls](int i, const ray<T>& r, const interval<T>& range) -> std::optional<hit_record<T>> {
        const T t = walls[size_t(i)];
        if (!range.surrounds(t)) return std::nullopt;
        hit_record<T> hit;
        hit.t = t;
        hit.point = r.at(t);
        hit.normal = vec3<T>(T(i), 0, 1);
        return hit;  // object stays -1: filling it in is the loop's job
    };
    return served;
}

// The calls the lecture's loop makes: object 0, 1, 2, ... each asked about
// (caller's tmin, closest t so far).
template <class T>
std::vector<rt::test::expected_call<T>> loop_calls(const std::vector<T>& walls, interval<T> range) {
    std::vector<rt::test::expected_call<T>> calls;
    for (size_t i = 0; i < walls.size(); ++i) {
        calls.push_back({int(i), range});
        if (range.surrounds(walls[i])) range.max = walls[i];
    }
    return calls;
}

template <class T>
ray<T> straight_ahead() {
    return {{0, 0, 0}, {0, 0, -1}};
}

template <class T>
interval<T> everything_ahead() {
    return {T(0), infinity<T>};
}

template <class T>
std::string describe(const std::optional<hit_record<T>>& hit) {
    if (!hit) return "a miss (std::nullopt)";
    std::ostringstream s;
    s << "t = " << hit->t << " on object " << hit->object;
    return s.str();
}

template <class T>
std::string list(const std::vector<T>& walls) {
    std::ostringstream s;
    for (size_t i = 0; i < walls.size(); ++i) s << (i ? ", " : "") << "object " << i << " at t = " << walls[i];
    return s.str();
}

// What a wrong answer says about the loop that returned it. ctest may run the
// tests in any order, so each message names the mistake its own numbers point
// to (in the lecture's words), not only the idea its test was written for.
template <class T>
std::string diagnosis(const std::optional<hit_record<T>>& hit, const std::vector<T>& walls,
                      const interval<T>& range) {
    if (!hit) return "";
    std::ostringstream s;
    if (std::isnan(hit->t)) return ". A NaN t is never a hit: return the record an object gave you, unchanged.";
    if (hit->object == -1)
        return ". The object tests leave `object` at -1: the loop knows which i it asked and must set "
               "hit.object = i.";
    if (!(hit->t > range.min)) {
        s << ". That t is not beyond the caller's tmin = " << range.min
          << ": pass the caller's tmin on to every object unchanged (do not replace it with 0 or an epsilon).";
        return s.str();
    }
    if (!(hit->t < range.max)) {
        s << ". That t is beyond the caller's tmax = " << range.max << ": start the loop from the caller's range.";
        return s.str();
    }
    std::vector<size_t> in_range;
    for (size_t i = 0; i < walls.size(); ++i)
        if (range.surrounds(walls[i])) in_range.push_back(i);
    if (in_range.empty()) return "";
    size_t nearest = in_range.front();
    for (size_t i : in_range)
        if (walls[i] < walls[nearest]) nearest = i;
    if (hit->t != walls[nearest]) {
        if (in_range.size() > 1 && hit->t == walls[in_range.front()])
            return ". That is the first object hit in the list: the loop must not stop at its first hit, a later "
                   "object may be nearer.";
        if (in_range.size() > 1 && hit->t == walls[in_range.back()])
            return ". That is the last object hit in the list: every hit replaced the best one, even a farther "
                   "one. Shrink tmax to the closest t so far, so a farther object cannot win.";
        if (nearest == 0) return ". The nearest is object 0: does the loop start at i = 0?";
        if (nearest + 1 == walls.size()) return ". The nearest is the last object: does the loop run up to i < object_count?";
        return "";
    }
    if (hit->object != int(nearest)) {
        s << ". t = " << hit->t << " is object " << nearest << "'s hit, but hit.object says " << hit->object
          << ": set hit.object = i, the index the loop asked.";
        return s.str();
    }
    if (hit->normal.x != T(hit->object))
        return ". The record mixes objects: return the nearest object's own hit record (its t, point and normal).";
    return "";
}

}  // namespace

TEST_CASE_TEMPLATE("the closest of several hits wins", T, RT_SCALARS) {
    const std::vector<T> walls{T(5), T(2), T(8)};
    auto hit = closest_hit<T>(3, walls_at(walls), straight_ahead<T>(), everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "every object is hit in (0, inf) (" << list(walls) << "); got a miss");
    CHECK_MESSAGE(close(hit->t, T(2)),
                  "the ray sees the nearest surface: of " << list(walls) << " the smallest t is 2. Got "
                                                          << describe(hit)
                                                          << diagnosis(hit, walls, everything_ahead<T>()));
}

TEST_CASE_TEMPLATE("the hit says which object it came from", T, RT_SCALARS) {
    const std::vector<T> walls{T(5), T(2), T(8)};
    auto hit = closest_hit<T>(3, walls_at(walls), straight_ahead<T>(), everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "every object is hit in (0, inf) (" << list(walls) << "); got a miss");
    CHECK_MESSAGE(hit->object != -1,
                  "the object tests leave `object` at -1; the loop knows which i it asked and must set "
                  "hit.object = i. Got "
                      << describe(hit));
    CHECK_MESSAGE((hit->object == -1 || hit->object == 1),
                  "of " << list(walls) << " the nearest is object 1, so hit.object must be 1; got "
                        << describe(hit) << diagnosis(hit, walls, everything_ahead<T>()));
    CHECK_MESSAGE(hit->normal.x == T(1),
                  "return the nearest object's own hit record (its t, point and normal), not a mix of "
                  "records; got a normal from object "
                      << hit->normal.x);
}

TEST_CASE_TEMPLATE("the answer does not depend on the order of the objects", T, RT_SCALARS) {
    std::vector<T> walls{T(3), T(7), T(1.5), T(4), T(9)};
    std::sort(walls.begin(), walls.end());
    do {
        auto hit = closest_hit<T>(5, walls_at(walls), straight_ahead<T>(), everything_ahead<T>());
        const size_t nearest = size_t(std::min_element(walls.begin(), walls.end()) - walls.begin());
        const bool ok = hit && close(hit->t, T(1.5)) && hit->object == int(nearest);
        CHECK_MESSAGE(ok, "the closest hit is the same surface whatever order the objects are listed in (ask "
                          "every object, 0 to object_count-1, and keep the nearest). With "
                              << list(walls) << " the answer is t = 1.5 on object " << nearest << "; got "
                              << describe(hit) << diagnosis(hit, walls, everything_ahead<T>()));
        if (!ok) break;  // one counter-example is enough to read
    } while (std::next_permutation(walls.begin(), walls.end()));
}

TEST_CASE_TEMPLATE("nothing beyond tmax is hit", T, RT_SCALARS) {
    const std::vector<T> walls{T(5), T(8)};
    auto hit = closest_hit<T>(2, walls_at(walls), straight_ahead<T>(), interval<T>{T(0), T(4)});
    CHECK_MESSAGE(!hit.has_value(),
                  "every object (" << list(walls) << ") is beyond tmax = 4: pass the caller's range on, and the "
                                      "answer is a miss; got "
                                   << describe(hit) << diagnosis(hit, walls, interval<T>{T(0), T(4)}));
}

TEST_CASE_TEMPLATE("nothing before tmin is hit", T, RT_SCALARS) {
    // A primary ray only sees what lies beyond the image plane, t > 1.
    const std::vector<T> walls{T(0.5), T(3)};
    auto hit = closest_hit<T>(2, walls_at(walls), straight_ahead<T>(), interval<T>::in_front_of_image_plane());
    REQUIRE_MESSAGE(hit.has_value(), "object 1 at t = 3 is in front of the image plane (t > 1); got a miss");
    CHECK_MESSAGE(close(hit->t, T(3)),
                  "object 0 at t = 0.5 lies between the eye and the image plane, so it must not count: keep "
                  "the caller's tmin when you ask each object. Expected t = 3 on object 1; got "
                      << describe(hit) << diagnosis(hit, walls, interval<T>::in_front_of_image_plane()));
    CHECK_MESSAGE(hit->object == 1, "t = 3 is object 1's hit, so hit.object must be 1; got "
                                        << describe(hit)
                                        << diagnosis(hit, walls, interval<T>::in_front_of_image_plane()));
}

TEST_CASE_TEMPLATE("an empty scene is a miss", T, RT_SCALARS) {
    // No call allowed: the record of the calls says whether one was made.
    auto nothing = walls_at(std::vector<T>{});
    nothing.budget = 0;
    const auto got = rt::test::call_with_rules<T>(
        [&] { return closest_hit<T>(0, nothing, straight_ahead<T>(), everything_ahead<T>()); });
    CHECK_MESSAGE(!got.broken, "with object_count = 0 there is no object to ask; the intersector was called");
    CHECK_MESSAGE(!got.answer.has_value(), "with no objects there is nothing to hit; got " << describe(got.answer));
}

TEST_CASE_TEMPLATE("each hit shrinks tmax for the objects after it", T, RT_SCALARS) {
    // The calls must be object 0, 1, 2, 3 in this order, each with the
    // caller's tmin and tmax shrunk to the closest t so far; the record of
    // the calls keeps the first one that differs.
    const std::vector<T> walls{T(5), T(2), T(8), T(1)};
    const interval<T> start{T(0.25), T(100)};
    const auto expected = loop_calls(walls, start);
    auto checking = walls_at(walls);
    checking.check_calls = true;
    checking.expected = expected;
    const auto got =
        rt::test::call_with_rules<T>([&] { return closest_hit<T>(4, checking, straight_ahead<T>(), start); });
    if (const auto& fault = got.broken) {
        const int k = int(fault->call);
        const bool in_order = k >= 0 && k < 4 && fault->object == k;
        CHECK_MESSAGE(in_order, "test every object exactly once, in order 0, 1, 2, 3; call "
                                    << k + 1 << " asked object " << fault->object);
        if (in_order) {
            CHECK_MESSAGE(fault->range.min == start.min, "every object is asked with the caller's tmin = 0.25; object "
                                                             << k << " was asked with tmin = " << fault->range.min);
            CHECK_MESSAGE(fault->range.max == expected[size_t(k)].range.max,
                          "after each hit, tmax shrinks to the closest t found so far, so farther objects cannot "
                          "win. With "
                              << list(walls) << ", object " << k << " should be asked with tmax = "
                              << expected[size_t(k)].range.max << " but was asked with tmax = " << fault->range.max);
        }
        return;
    }
    const auto& hit = got.answer;
    REQUIRE_MESSAGE(hit.has_value(), "every object is hit in (0.25, 100) (" << list(walls) << "); got a miss");
    CHECK_MESSAGE((close(hit->t, T(1)) && hit->object == 3),
                  "the nearest is t = 1 on object 3; got " << describe(hit) << diagnosis(hit, walls, start));
    CHECK_MESSAGE(hit->normal.x == T(3), "test every object exactly once, in order 0, 1, 2, 3: the answer is not "
                                         "the record of object 3, the last and nearest one");
}
