// Public tests for chapter 08, exercise 2: closest_hit and any_hit (bvh.hpp).
//
// The trees here come from the GIVEN median builder, so these tests need only
// your slab test and your traversal. The rule throughout: the tree's answer
// equals brute force's exactly (same object, same bits of t), because a BVH is
// only a faster way to ask the same question.
#include "ch08_scenes.hpp"
#include "08-acceleration/median_build.hpp"

#include "test_support.hpp"

using namespace rt;
using namespace rt::ch08;
using namespace rt::ch08::test;
using rt::test::describe_hit;

namespace {

template <class T>
std::string object_of(const std::optional<hit_record<T>>& hit) {
    return hit ? "object " + std::to_string(hit->object) + ", " + describe_hit(hit) : describe_hit(hit);
}

// Compares the tree with brute force on `rays` random rays; returns how many differ
// and describes the first one.
template <class T>
int count_differences(const objects<T>& scene, const bvh<T>& tree, std::mt19937_64& rng, int rays, double size,
                      std::string& first) {
    int differ = 0;
    const auto intersect = scene.intersector();
    for (int i = 0; i < rays; ++i) {
        const ray<T> r = random_ray<T>(rng, size);
        const interval<T> range{T(0), infinity<T>};
        const auto want = brute_force(scene, r, range);
        const auto got = closest_hit(tree, intersect, r, range);
        if (same_answer(want, got)) continue;
        if (differ++ == 0)
            first = "ray from " + rt::test::describe(r.origin) + " along " + rt::test::describe(r.direction) +
                    ": brute force finds " + object_of(want) + "; the tree finds " + object_of(got);
    }
    return differ;
}

}  // namespace

TEST_CASE_TEMPLATE("traversal: an empty tree is a miss, and no object is asked", T, RT_SCALARS) {
    const objects<T> scene;
    const bvh<T> tree = build_median(scene.boxes());
    const ray<T> r{{0, 0, 0}, {0, 0, -1}};
    // A budget of no calls: the record of the calls says whether one was made.
    const auto got = rt::test::call_with_rules<T>(
        [&] { return closest_hit(tree, scene.intersector(0), r, rt::test::everything_ahead<T>()); });
    CHECK_MESSAGE(!got.broken, "with no objects, intersect must never be called (there is no index to give it)");
    CHECK_MESSAGE(!got.answer, "a tree of no objects has no nodes (tree.nodes is empty): nothing can be hit");
    const auto any = rt::test::call_with_rules<T>(
        [&] { return any_hit(tree, scene.intersector(0), r, rt::test::everything_ahead<T>()); });
    CHECK_MESSAGE((!any.answer && !any.broken),
                  "any_hit on an empty tree: nothing can be hit, and intersect must never be called");
}

TEST_CASE_TEMPLATE("traversal: one object: the tree gives exactly brute force's hit", T, RT_SCALARS) {
    objects<T> scene;
    scene.spheres.push_back({{0, 0, -5}, T(1)});
    const bvh<T> tree = build_median(scene.boxes());
    const ray<T> r{{T(0.25), 0, 0}, {0, 0, -1}};
    const auto want = brute_force(scene, r, rt::test::everything_ahead<T>());
    const auto got = closest_hit(tree, scene.intersector(), r, rt::test::everything_ahead<T>());
    REQUIRE_MESSAGE(got.has_value(), "the ray passes 0.25 from the centre of the only sphere: a hit");
    CHECK_MESSAGE(same_answer(want, got), "the tree must return the object's own hit record with `object` set to "
                                          "its index (0): brute force gives "
                                              << object_of(want) << "; the tree gives " << object_of(got));
    const ray<T> away{{T(0.25), 0, 0}, {0, 0, 1}};
    CHECK_MESSAGE(!closest_hit(tree, scene.intersector(), away, rt::test::everything_ahead<T>()),
                  "a ray pointing away from the only sphere misses it");
}

TEST_CASE_TEMPLATE("traversal: the nearest hit wins even when another leaf is visited first", T, RT_SCALARS) {
    // Two leaves whose boxes overlap along the ray. Object 0, a big sphere,
    // has the box the ray enters first (at t = 6) but is hit only at t = 8.06;
    // object 1, a small sphere, has a box entered later (t = 7.2) and is hit
    // nearer, at t = 7.2. Nearest child first visits object 0's leaf first:
    // its hit is not yet the answer.
    objects<T> scene;
    scene.spheres.push_back({{0, 3, -10}, T(4)});        // box y in [-1, 7], z in [-14, -6]
    scene.spheres.push_back({{0, T(-0.5), T(-7.5)}, T(0.3)});  // box z in [-7.8, -7.2]
    build_options one_per_leaf;
    one_per_leaf.max_leaf_size = 1;
    const bvh<T> tree = build_median(scene.boxes(), one_per_leaf);
    const ray<T> r{{0, T(-0.5), 0}, {0, 0, -1}};
    const auto want = brute_force(scene, r, rt::test::everything_ahead<T>());
    REQUIRE(want.has_value());
    REQUIRE(want->object == 1);
    const auto got = closest_hit(tree, scene.intersector(), r, rt::test::everything_ahead<T>());
    REQUIRE_MESSAGE(got.has_value(), "the ray along -z at y = -0.5 hits both spheres");
    CHECK_MESSAGE(got->object != 0,
                  "the search stopped at the first leaf with a hit. The ray enters the big sphere's box first (t = "
                  "6) and hits the sphere at t = 8.06, but the small sphere's box, entered later (t = 7.2), holds a "
                  "nearer hit (t = 7.2). Boxes overlap: a hit in one leaf is only the best SO FAR. Keep popping "
                  "the nodes that wait on the stack and skip only those whose entry lies beyond the best t "
                  "(entry > widen_exit(best t)). Got "
                      << object_of(got));
    CHECK_MESSAGE(same_answer(want, got), "brute force finds " << object_of(want) << "; the tree finds "
                                                               << object_of(got));

    // A row of spheres along -z, one per leaf: the ray along the row crosses
    // all of them; only the nearest is the answer.
    objects<T> row;
    for (int i = 0; i < 8; ++i) row.spheres.push_back({{0, 0, T(-3 * i - 3)}, T(1)});
    const bvh<T> row_tree = build_median(row.boxes(), one_per_leaf);
    for (T dz : {T(-1), T(1)}) {
        const ray<T> along{{0, 0, dz < 0 ? T(0) : T(-30)}, {0, 0, dz}};
        const auto nearest = brute_force(row, along, rt::test::everything_ahead<T>());
        const auto found = closest_hit(row_tree, row.intersector(), along, rt::test::everything_ahead<T>());
        CHECK_MESSAGE(same_answer(nearest, found),
                      "a ray along the row of 8 spheres hits every one of them; the answer is the nearest ("
                          << object_of(nearest) << "). Got " << object_of(found)
                          << ". A farther one means the leaf's objects were asked about the whole range instead "
                             "of (range.min, best t so far), or the far child was visited first and its hit kept");
    }
}

TEST_CASE_TEMPLATE("traversal: nearest child first, and boxes beyond the closest hit are skipped", T, RT_SCALARS) {
    // 32 spheres in a row along +x, one per leaf. A ray along the row hits
    // all of them; a tree walked nearest-first finds the first sphere, and
    // every other box then starts beyond that hit and is skipped.
    objects<T> scene;
    for (int i = 0; i < 32; ++i) scene.spheres.push_back({{T(3 * i + 3), 0, 0}, T(1)});
    build_options one_per_leaf;
    one_per_leaf.max_leaf_size = 1;
    const bvh<T> tree = build_median(scene.boxes(), one_per_leaf);
    const ray<T> r{{0, T(0.25), 0}, {1, 0, 0}};
    // At most 3 objects may be asked: the record of the calls keeps a 4th.
    const auto checked = rt::test::call_with_rules<T>(
        [&] { return closest_hit(tree, scene.intersector(3), r, rt::test::everything_ahead<T>()); });
    CHECK_MESSAGE(!checked.broken, "the traversal asked more than 3 of the 32 spheres; nearest first, it needs 1 (or 2 "
                                   "or 3 where boxes touch). Visit the child with the smaller entry first (push the "
                                   "farther one first), and when you pop a node whose entry lies beyond the closest "
                                   "hit so far (entry > widen_exit(best t)), skip it");
    if (checked.broken) return;
    const auto& got = checked.answer;
    REQUIRE_MESSAGE(got.has_value(), "the ray along the row hits every sphere");
    CHECK_MESSAGE(got->object == 0, "the nearest sphere is object 0; got " << object_of(got));
}

TEST_CASE_TEMPLATE("traversal: equal t: the lowest object index wins, whatever order the tree visits", T, RT_SCALARS) {
    // The same sphere three times, at indices 1, 4 and 6, among others; the
    // copies are hit at exactly the same t. Brute force keeps index 1.
    objects<T> scene;
    const sphere<T> twin{{0, 0, -5}, T(1)};
    const sphere<T> others[] = {{{3, 0, -5}, T(1)}, {{-3, 0, -5}, T(1)}, {{0, 3, -5}, T(1)}, {{0, -3, -5}, T(1)}};
    scene.spheres = {others[0], twin, others[1], others[2], twin, others[3], twin};
    build_options one_per_leaf;
    one_per_leaf.max_leaf_size = 1;
    const bvh<T> tree = build_median(scene.boxes(), one_per_leaf);
    const ray<T> r{{T(0.1), T(0.2), 0}, {0, 0, -1}};
    const auto got = closest_hit(tree, scene.intersector(), r, rt::test::everything_ahead<T>());
    REQUIRE_MESSAGE(got.has_value(), "the ray hits the sphere at (0, 0, -5), present three times");
    CHECK_MESSAGE(got->object == 1,
                  "objects 1, 4 and 6 are the same sphere, hit at exactly the same t; brute force (0, 1, 2, ...) "
                  "keeps the first, object 1, and so must the tree. The tree may meet object 4 or 6 first: in a "
                  "leaf, ask each object up to AND INCLUDING the best t (range.max = the next number above it, "
                  "std::nextafter), and replace the best hit on an equal t when the index is lower. Got "
                      << object_of(got));
}

TEST_CASE_TEMPLATE("traversal: random spheres: the tree's closest hit is brute force's, bit for bit", T, RT_SCALARS) {
    std::mt19937_64 rng(8001);
    objects<T> scene;
    add_random_spheres(scene, rng, 300, 10, 0.05, 0.8);
    const bvh<T> tree = build_median(scene.boxes());
    std::string first;
    const int differ = count_differences(scene, tree, rng, 400, 12, first);
    CHECK_MESSAGE(differ == 0, differ << " of 400 rays through 300 random spheres got another answer from the tree "
                                         "than from brute force. First: "
                                      << first);
}

TEST_CASE_TEMPLATE("traversal: random triangles and a flat mesh: the tree's closest hit is brute force's", T, RT_SCALARS) {
    std::mt19937_64 rng(8002);
    objects<T> scene;
    add_random_triangles(scene, rng, 200, 5, 1.5);
    add_planar_grid(scene, 8, T(0.25));  // 128 triangles with flat boxes, sharing edges
    add_random_spheres(scene, rng, 50, 5, 0.1, 0.5);
    const bvh<T> tree = build_median(scene.boxes());
    std::string first;
    const int differ = count_differences(scene, tree, rng, 400, 6, first);
    CHECK_MESSAGE(differ == 0, differ << " of 400 rays through triangles, a flat mesh and spheres got another answer "
                                         "from the tree than from brute force. First: "
                                      << first);

    // Straight down through the flat mesh, through its shared edges and corners:
    // two or more triangles are hit at the same t, the lowest index wins.
    int wrong = 0;
    std::string first_wrong;
    for (int i = -8; i <= 8; ++i) {
        const ray<T> down{{T(i) / T(8), T(3), T(i) / T(16)}, {0, -1, 0}};
        const auto want = brute_force(scene, down, rt::test::everything_ahead<T>());
        const auto got = closest_hit(tree, scene.intersector(), down, rt::test::everything_ahead<T>());
        if (!same_answer(want, got) && wrong++ == 0)
            first_wrong = "down from " + rt::test::describe(down.origin) + ": brute force " + object_of(want) +
                          ", tree " + object_of(got);
    }
    CHECK_MESSAGE(wrong == 0, wrong << " rays straight down (direction x and z components 0) through edges and "
                                       "corners of the flat mesh got another answer than brute force. Flat boxes "
                                       "must be entered (<=), zero direction components must not produce NaN "
                                       "misses, and equal t must go to the lowest index. First: "
                                    << first_wrong);
}

TEST_CASE_TEMPLATE("traversal: any_hit says whether closest_hit finds something", T, RT_SCALARS) {
    std::mt19937_64 rng(8003);
    objects<T> scene;
    add_random_spheres(scene, rng, 100, 10, 0.1, 1.0);
    add_random_triangles(scene, rng, 100, 10, 2.0);
    const bvh<T> tree = build_median(scene.boxes());
    const auto intersect = scene.intersector();
    int disagree = 0, hits = 0;
    for (int i = 0; i < 400; ++i) {
        const ray<T> r = random_ray<T>(rng, 12);
        // Shadow rays look at a segment: (0, |to - from|) of a unit direction.
        std::uniform_real_distribution<double> length(0.5, 8);
        const interval<T> segment{T(0), T(length(rng))};
        const ray<T> unit{r.origin, normalize(r.direction)};
        const bool closest = closest_hit(tree, intersect, unit, segment).has_value();
        hits += closest;
        if (any_hit(tree, intersect, unit, segment) != closest) ++disagree;
    }
    REQUIRE(hits > 20);
    CHECK_MESSAGE(disagree == 0, "any_hit disagreed with closest_hit on " << disagree
                                     << " of 400 shadow-ray segments. It must be true exactly when something is "
                                        "hit with range.min < t < range.max: same boxes, same range, no shrinking");
}
