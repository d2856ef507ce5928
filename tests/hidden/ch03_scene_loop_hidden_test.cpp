// Hidden tests for chapter 03: the closest hit among many objects.
//
// Most objects here are "walls": object i is met at one known parameter
// walls[i] (or never, when that is NaN), honouring the open range it is
// asked about. Its hit record carries a tag in the normal so a test can tell
// whose record came back. The last cases use real spheres (chapter 02's
// reference) in seeded random scenes. A failure names the concept that went
// wrong, never the expected values.
#include "03-scene-loop/scene_loop.hpp"
#include "02-sphere/sphere.hpp"

#include "rpc/served.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

using namespace rt;
using rt::ch03::closest_hit;

namespace {

template <class T>
T never() {
    return std::numeric_limits<T>::quiet_NaN();  // a wall the ray never meets: surrounds(NaN) is false
}

// Object i is met at walls[i]; its record's normal is (tags[i], 0, 1). A
// served callback (tests/support/rpc/served.hpp): the judge answers each call
// of the runner with the walls' own test. A call about an object outside
// 0 .. n-1, beyond a budget, or other than the expected next one is kept in
// the judge's record of the calls, and closest_hit then fails with
// rt::test::broken_rule whatever it returns (call_with_rules reads it).
template <class T>
rt::test::served_objects<T> walls_at(const std::vector<T>& walls, const std::vector<int>& tags) {
    rt::test::served_objects<T> served;
    served.count = int(walls.size());
    served.test = [walls, tags](int i, const ray<T>& r, const interval<T>& range) -> std::optional<hit_record<T>> {
        const T t = walls[size_t(i)];
        if (!range.surrounds(t)) return std::nullopt;
        hit_record<T> hit;
        hit.t = t;
        hit.point = r.at(t);
        hit.normal = vec3<T>(T(tags[size_t(i)]), 0, 1);
        return hit;
    };
    return served;
}

template <class T>
rt::test::served_objects<T> walls_at(const std::vector<T>& walls) {
    std::vector<int> tags(walls.size());
    std::iota(tags.begin(), tags.end(), 0);
    return walls_at(walls, tags);
}

// The same walls, with every call checked: object 0, 1, 2, ... each asked
// about (caller's tmin, closest t so far), and nothing after.
template <class T>
rt::test::served_objects<T> walls_checking_calls(const std::vector<T>& walls, interval<T> range) {
    rt::test::served_objects<T> served = walls_at(walls);
    served.check_calls = true;
    for (size_t i = 0; i < walls.size(); ++i) {
        served.expected.push_back({int(i), range});
        if (range.surrounds(walls[i])) range.max = walls[i];
    }
    return served;
}

template <class T>
ray<T> forward() {
    return {{0, 0, 0}, {0, 0, -1}};
}

template <class T>
interval<T> ahead() {
    return {T(0), infinity<T>};
}

// The answer by brute force: the smallest wall inside the range (first on ties).
template <class T>
int nearest_wall(const std::vector<T>& walls, const interval<T>& range) {
    int best = -1;
    for (size_t i = 0; i < walls.size(); ++i)
        if (range.surrounds(walls[i]) && (best < 0 || walls[i] < walls[size_t(best)])) best = int(i);
    return best;
}

// The loop's answer is right when it is the wall brute force finds: same t,
// the object index set to it, and that object's own record.
template <class T>
bool is_nearest(const std::optional<hit_record<T>>& hit, const std::vector<T>& walls, const interval<T>& range) {
    const int best = nearest_wall(walls, range);
    if (best < 0) return !hit.has_value();
    return hit.has_value() && hit->t == walls[size_t(best)] && hit->object >= 0 &&
           size_t(hit->object) < walls.size() && walls[size_t(hit->object)] == hit->t &&
           hit->normal.x == T(hit->object);
}

template <class T>
std::vector<T> random_walls(std::mt19937& rng, int count, T lo, T hi, double miss_chance) {
    std::uniform_real_distribution<T> where(lo, hi);
    std::bernoulli_distribution missed(miss_chance);
    std::vector<T> walls(static_cast<size_t>(count));
    for (auto& w : walls) w = missed(rng) ? never<T>() : where(rng);
    return walls;
}

constexpr int random_scenes = 500;

}  // namespace

// ---- the public cases, with other numbers ------------------------------------

TEST_CASE_TEMPLATE("the nearest of many objects is returned", T, RT_SCALARS) {
    const std::vector<T> walls{T(9), T(4), T(6), T(3.5), T(12), T(7)};
    auto hit = closest_hit<T>(6, walls_at(walls), forward<T>(), ahead<T>());
    const bool ok = is_nearest(hit, walls, ahead<T>());
    CHECK_MESSAGE(ok, "the ray sees the surface with the smallest t in range");
}

TEST_CASE_TEMPLATE("the object index of the nearest hit is filled in", T, RT_SCALARS) {
    const std::vector<T> walls{T(9), T(4), T(6), T(3.5), T(12), T(7)};
    auto hit = closest_hit<T>(6, walls_at(walls), forward<T>(), ahead<T>());
    const bool ok = hit.has_value() && hit->object == 3;
    CHECK_MESSAGE(ok, "the loop sets hit.object to the index i of the object that was hit");
}

TEST_CASE_TEMPLATE("the record returned belongs to the nearest object", T, RT_SCALARS) {
    const std::vector<T> walls{T(9), T(4), T(6), T(3.5), T(12), T(7)};
    auto hit = closest_hit<T>(6, walls_at(walls), forward<T>(), ahead<T>());
    const bool ok = hit.has_value() && hit->normal.x == T(3) && hit->point == forward<T>().at(T(3.5));
    CHECK_MESSAGE(ok, "the nearest object's own record comes back: its t, point and normal");
}

TEST_CASE_TEMPLATE("listing the objects in any order gives the same hit", T, RT_SCALARS) {
    std::mt19937 rng(12345u);
    bool ok = true;
    for (int n = 1; n <= 8 && ok; ++n) {
        for (int trial = 0; trial < 60 && ok; ++trial) {
            std::vector<T> walls = random_walls<T>(rng, n, T(0.5), T(50), 0.3);
            std::vector<int> tags(static_cast<size_t>(n));
            std::iota(tags.begin(), tags.end(), 0);
            auto first = closest_hit<T>(n, walls_at(walls, tags), forward<T>(), ahead<T>());
            // A wrong answer may carry any object index: look it up only when it is one of ours.
            const bool first_valid = first && first->object >= 0 && first->object < n;
            const int first_tag = first_valid ? tags[size_t(first->object)] : -1;
            // The same objects, shuffled: the surface hit (its tag) and t must not change.
            std::vector<size_t> order(static_cast<size_t>(n));
            std::iota(order.begin(), order.end(), size_t(0));
            std::shuffle(order.begin(), order.end(), rng);
            std::vector<T> shuffled_walls(static_cast<size_t>(n));
            std::vector<int> shuffled_tags(static_cast<size_t>(n));
            for (size_t k = 0; k < size_t(n); ++k) {
                shuffled_walls[k] = walls[order[k]];
                shuffled_tags[k] = tags[order[k]];
            }
            auto again = closest_hit<T>(n, walls_at(shuffled_walls, shuffled_tags), forward<T>(), ahead<T>());
            const bool same_miss = !first && !again;
            const bool same_hit = first_valid && again && first->t == again->t && again->object >= 0 &&
                                  again->object < n && first_tag == int(again->normal.x) &&
                                  shuffled_tags[size_t(again->object)] == first_tag;
            ok = (same_miss || same_hit) && is_nearest(first, walls, ahead<T>());
        }
    }
    CHECK_MESSAGE(ok, "the closest hit does not depend on the order in which objects are listed");
}

TEST_CASE_TEMPLATE("objects at or beyond tmax are not hit", T, RT_SCALARS) {
    const std::vector<T> walls{T(8), T(5), T(9)};
    const bool beyond = !closest_hit<T>(3, walls_at(walls), forward<T>(), interval<T>{T(0), T(4)}).has_value();
    const bool at = !closest_hit<T>(3, walls_at(walls), forward<T>(), interval<T>{T(0), T(5)}).has_value();
    auto some = closest_hit<T>(3, walls_at(walls), forward<T>(), interval<T>{T(0), T(8.5)});
    const bool partly = is_nearest(some, walls, interval<T>{T(0), T(8.5)});
    CHECK_MESSAGE(beyond, "objects beyond the caller's tmax are not hit");
    CHECK_MESSAGE(at, "an object exactly at tmax is not hit (t < tmax is strict)");
    CHECK_MESSAGE(partly, "only objects inside the caller's range compete");
}

TEST_CASE_TEMPLATE("objects at or before tmin are not hit", T, RT_SCALARS) {
    const std::vector<T> walls{T(0.5), T(1), T(3), T(0.75)};
    auto hit = closest_hit<T>(4, walls_at(walls), forward<T>(), interval<T>::in_front_of_image_plane());
    const bool ok = hit.has_value() && hit->t == T(3) && hit->object == 2;
    CHECK_MESSAGE(ok, "the caller's tmin is kept: objects at or before it (here the image plane t = 1) do not count");
}

TEST_CASE_TEMPLATE("no objects means a miss without asking anything", T, RT_SCALARS) {
    // No call allowed: the record of the calls says whether one was made.
    auto counting = walls_at(std::vector<T>{});
    counting.budget = 0;
    const auto empty = rt::test::call_with_rules<T>([&] { return closest_hit<T>(0, counting, forward<T>(), ahead<T>()); });
    const auto negative =
        rt::test::call_with_rules<T>([&] { return closest_hit<T>(-3, counting, forward<T>(), ahead<T>()); });
    const bool empty_miss = !empty.answer.has_value();
    const bool negative_miss = !negative.answer.has_value();
    const bool nothing_asked = !empty.broken && !negative.broken;
    CHECK_MESSAGE(empty_miss, "an empty scene is a miss");
    CHECK_MESSAGE(negative_miss, "a negative object count is an empty scene: a miss");
    CHECK_MESSAGE(nothing_asked, "with no objects the intersector is never called");
}

TEST_CASE_TEMPLATE("each object is tested with tmax shrunk to the closest hit so far", T, RT_SCALARS) {
    std::mt19937 rng(777u);
    bool ranges_ok = true, each_once = true;
    for (int trial = 0; trial < random_scenes; ++trial) {
        const int n = 1 + trial % 9;
        const std::vector<T> walls = random_walls<T>(rng, n, T(0.1), T(40), 0.25);
        const interval<T> start{T(trial % 3 == 0 ? 0.0 : 0.5), trial % 2 == 0 ? infinity<T> : T(30)};
        const auto checked = rt::test::call_with_rules<T>(
            [&] { return closest_hit<T>(n, walls_checking_calls(walls, start), forward<T>(), start); });
        const auto& hit = checked.answer;
        if (const auto& fault = checked.broken) {
            // The first call that broke the order, or asked about another range.
            if (fault->call >= n || fault->object != fault->call) each_once = false;
            else ranges_ok = false;
            break;
        }
        // Every call so far was the expected one. The answer is the record of the
        // nearest wall (its t and tag; the index is another test's) only if the
        // loop went on asking up to the last object.
        const int best = nearest_wall(walls, start);
        const bool got_nearest = best < 0 ? !hit.has_value()
                                          : hit.has_value() && hit->t == walls[size_t(best)] && hit->normal.x == T(best);
        if (!got_nearest) {
            each_once = false;
            break;
        }
    }
    CHECK_MESSAGE(each_once, "every object is tested exactly once, in order 0 .. object_count-1");
    CHECK_MESSAGE(ranges_ok, "object i is asked about (tmin, closest t so far): each hit shrinks tmax");
}

// ---- more cases ----------------------------------------------------------------

TEST_CASE_TEMPLATE("random scenes of walls give the nearest hit", T, RT_SCALARS) {
    std::mt19937 rng(2026u);
    bool ok = true;
    for (int trial = 0; trial < random_scenes && ok; ++trial) {
        const int n = 1 + trial % 12;
        const std::vector<T> walls = random_walls<T>(rng, n, T(-20), T(60), 0.2);
        const interval<T> range{T(trial % 4 == 0 ? -infinity<T> : T(1)), trial % 3 == 0 ? T(25) : infinity<T>};
        ok = is_nearest(closest_hit<T>(n, walls_at(walls), forward<T>(), range), walls, range);
    }
    CHECK_MESSAGE(ok, "over random scenes the loop returns the nearest object inside (tmin, tmax), with its index");
}

TEST_CASE_TEMPLATE("the nearest object may be the first one listed", T, RT_SCALARS) {
    const std::vector<T> walls{T(2), T(4), T(6)};
    auto hit = closest_hit<T>(3, walls_at(walls), forward<T>(), ahead<T>());
    const bool ok = is_nearest(hit, walls, ahead<T>());
    CHECK_MESSAGE(ok, "object 0 is an object like any other: start the loop at i = 0");
}

TEST_CASE_TEMPLATE("the nearest object may be the last one listed", T, RT_SCALARS) {
    const std::vector<T> walls{T(6), T(4), T(2)};
    auto hit = closest_hit<T>(3, walls_at(walls), forward<T>(), ahead<T>());
    const bool ok = is_nearest(hit, walls, ahead<T>());
    CHECK_MESSAGE(ok, "keep looking after the first hit: a later object may be nearer");
}

TEST_CASE_TEMPLATE("a single object is found", T, RT_SCALARS) {
    const std::vector<T> walls{T(5)};
    auto hit = closest_hit<T>(1, walls_at(walls), forward<T>(), ahead<T>());
    const bool ok = is_nearest(hit, walls, ahead<T>());
    CHECK_MESSAGE(ok, "a scene of one object: its hit is the closest");
}

TEST_CASE_TEMPLATE("objects that are missed do not disturb the answer", T, RT_SCALARS) {
    const std::vector<T> walls{never<T>(), T(7), never<T>(), T(3), never<T>(), T(5), never<T>()};
    auto hit = closest_hit<T>(7, walls_at(walls), forward<T>(), ahead<T>());
    const bool ok = is_nearest(hit, walls, ahead<T>());
    std::vector<T> all_missed(5, never<T>());
    const bool miss = !closest_hit<T>(5, walls_at(all_missed), forward<T>(), ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "a miss (std::nullopt) from one object leaves the best hit so far as it was");
    CHECK_MESSAGE(miss, "when every object is missed the answer is a miss");
}

TEST_CASE_TEMPLATE("equally near objects give one consistent hit", T, RT_SCALARS) {
    const std::vector<T> walls{T(9), T(4), T(6), T(4), T(4)};
    auto hit = closest_hit<T>(5, walls_at(walls), forward<T>(), ahead<T>());
    const bool ok = hit.has_value() && hit->t == T(4) &&
                    (hit->object == 1 || hit->object == 3 || hit->object == 4) && hit->normal.x == T(hit->object);
    CHECK_MESSAGE(ok, "on a tie the hit is at the shared t, with the index and record of one of the tied objects");
}

TEST_CASE_TEMPLATE("an empty range is a miss", T, RT_SCALARS) {
    const std::vector<T> walls{T(4), T(5), T(6)};
    const bool point = !closest_hit<T>(3, walls_at(walls), forward<T>(), interval<T>{T(5), T(5)}).has_value();
    const bool reversed = !closest_hit<T>(3, walls_at(walls), forward<T>(), interval<T>{T(7), T(3)}).has_value();
    CHECK_MESSAGE(point, "the open interval (5, 5) holds no t: nothing can be hit");
    CHECK_MESSAGE(reversed, "a range with tmin > tmax holds no t: nothing can be hit");
}

TEST_CASE_TEMPLATE("a range reaching behind the origin returns the smallest t", T, RT_SCALARS) {
    const std::vector<T> walls{T(2), T(-3), T(-1), T(5)};
    const interval<T> everywhere{-infinity<T>, infinity<T>};
    auto hit = closest_hit<T>(4, walls_at(walls), forward<T>(), everywhere);
    const bool ok = hit.has_value() && hit->t == T(-3) && hit->object == 1;
    CHECK_MESSAGE(ok, "the caller's range is the rule, even when it includes t < 0: keep its tmin and its tmax");
}

TEST_CASE_TEMPLATE("the ray is passed on unchanged", T, RT_SCALARS) {
    const ray<T> r{{T(1.5), T(-2), T(3)}, {T(0.25), T(0.5), T(-4)}};
    // Walls the ray never meets, asked about r alone: a call about another ray
    // breaks the test's rule.
    auto checking = walls_at(std::vector<T>(3, never<T>()));
    checking.only_ray = r;
    const bool same = !rt::test::call_with_rules<T>([&] { return closest_hit<T>(3, checking, r, ahead<T>()); }).broken;
    CHECK_MESSAGE(same, "every object is asked about the caller's ray itself");
}

// ---- real spheres --------------------------------------------------------------

TEST_CASE_TEMPLATE("random scenes of spheres agree with testing every sphere", T, RT_SCALARS) {
    std::mt19937 rng(4711u);
    std::uniform_real_distribution<T> coord(T(-6), T(6));
    std::uniform_real_distribution<T> depth(T(-30), T(-3));
    std::uniform_real_distribution<T> size(T(0.3), T(3));
    bool ok = true;
    int hits = 0;
    for (int trial = 0; trial < random_scenes && ok; ++trial) {
        const int n = 2 + trial % 15;
        std::vector<sphere<T>> spheres(static_cast<size_t>(n));
        for (auto& s : spheres) s = {{coord(rng), coord(rng), depth(rng)}, size(rng)};
        rt::test::served_objects<T> intersect;
        intersect.count = n;
        intersect.test = [&spheres](int i, const ray<T>& r, const interval<T>& range) {
            return ch02::intersect_sphere(spheres[size_t(i)], r, range);
        };
        const ray<T> r{{0, 0, 0}, {coord(rng) / T(8), coord(rng) / T(8), T(-1)}};
        const interval<T> range = interval<T>::in_front_of_image_plane();
        // Brute force: every sphere over the whole range, keep the smallest t.
        int best = -1;
        T best_t = infinity<T>;
        for (int i = 0; i < n; ++i) {
            auto h = ch02::intersect_sphere(spheres[size_t(i)], r, range);
            if (h && h->t < best_t) {
                best_t = h->t;
                best = i;
            }
        }
        auto hit = closest_hit<T>(n, intersect, r, range);
        if (best < 0) {
            ok = !hit.has_value();
        } else {
            ++hits;
            ok = hit.has_value() && hit->object == best && hit->t == best_t;
        }
    }
    const bool enough = hits > random_scenes / 5;
    CHECK_MESSAGE(enough, "rays into random scenes of spheres hit some of them");
    CHECK_MESSAGE(ok, "in scenes of spheres the loop finds the same sphere and t as testing every sphere");
}
