// Public tests for chapter 08, exercise 3: build_sah (bvh.hpp).
//
// A built tree is checked against the promises of struct bvh (every object
// exactly once, exact boxes, leaf sizes), then used: its answers must equal
// brute force's, and on a clustered scene its expected cost (sah_cost) must
// be lower than the median split's.
#include "ch08_scenes.hpp"
#include "08-acceleration/median_build.hpp"

#include "test_support.hpp"

#include <stdexcept>

using namespace rt;
using namespace rt::ch08;
using namespace rt::ch08::test;

namespace {

// Clusters of many small spheres around a few centres, plus a few big ones
// far apart: the median split cuts clusters in halves and makes boxes that
// span empty space; the SAH puts its planes in the gaps.
template <class T>
objects<T> clustered_scene(std::mt19937_64& rng) {
    objects<T> scene;
    const vec3d centres[] = {{-20, 0, 0}, {18, 3, -4}, {0, 15, 9}, {2, -16, 12}};
    std::normal_distribution<double> spread(0, 0.7);
    for (const vec3d& c : centres)
        for (int i = 0; i < 60; ++i)
            scene.spheres.push_back({convert<T>(c + vec3d(spread(rng), spread(rng), spread(rng))), T(0.1)});
    for (int i = 0; i < 4; ++i) scene.spheres.push_back({random_point<T>(rng, -25, 25), T(3)});
    return scene;
}

}  // namespace

TEST_CASE_TEMPLATE("sah: the SAH tree holds every object once, with exact boxes and small leaves", T, RT_SCALARS) {
    std::mt19937_64 rng(8101);
    objects<T> scene;
    add_random_spheres(scene, rng, 150, 10, 0.05, 1.0);
    add_random_triangles(scene, rng, 150, 10, 2.0);
    for (int leaf : {1, 4, 9}) {
        build_options options;
        options.max_leaf_size = leaf;
        const auto boxes = scene.boxes();
        const bvh<T> tree = build_sah_bounded(boxes, options);
        const std::string problem = tree_problem(tree, boxes, leaf);
        CHECK_MESSAGE(problem.empty(), "with max_leaf_size " << leaf << ": " << problem
                                                            << ". When you partition a node's objects, every object "
                                                               "goes to exactly one side, and each node's box is "
                                                               "the union of the boxes of the objects below it");
    }
    const bvh<T> none = build_sah_bounded(std::vector<aabb<T>>{});
    CHECK_MESSAGE((none.nodes.empty() && none.order.empty()), "no objects: an empty tree (no nodes)");
}

TEST_CASE_TEMPLATE("sah: objects whose centres coincide are still split down to the leaf size", T, RT_SCALARS) {
    // 40 copies of the same sphere: no binned plane separates them.
    objects<T> scene;
    for (int i = 0; i < 40; ++i) scene.spheres.push_back({{1, 2, 3}, T(0.5)});
    build_options options;
    options.max_leaf_size = 4;
    const auto boxes = scene.boxes();
    const bvh<T> tree = build_sah_bounded(boxes, options);
    const std::string problem = tree_problem(tree, boxes, 4);
    CHECK_MESSAGE(problem.empty(), problem << ". When every centre is the same point there is no candidate plane; a "
                                              "node with more than max_leaf_size objects is then cut in two halves");
    const ray<T> r{{1, 2, 0}, {0, 0, 1}};
    const auto got = closest_hit(tree, scene.intersector(), r, rt::test::everything_ahead<T>());
    REQUIRE_MESSAGE(got.has_value(), "the ray goes through the sphere's centre");
    CHECK_MESSAGE(got->object == 0, "40 copies of one sphere are hit at the same t: the lowest index, 0, wins");
}

TEST_CASE_TEMPLATE("sah: on a clustered scene the SAH tree is cheaper than the median tree", T, RT_SCALARS) {
    std::mt19937_64 rng(8102);
    const objects<T> scene = clustered_scene<T>(rng);
    const auto boxes = scene.boxes();
    const T median = sah_cost(build_median(boxes));
    const bvh<T> sah_tree = build_sah_bounded(boxes);
    const std::string problem = tree_problem(sah_tree, boxes, build_options{}.max_leaf_size);
    REQUIRE_MESSAGE(problem.empty(), problem);
    const T sah = sah_cost(sah_tree);
    CHECK_MESSAGE(sah < T(0.8) * median,
                  "expected cost (sah_cost) of the SAH tree: " << sah << ", of the median tree: " << median
                      << ". The SAH tree should be clearly cheaper (below 80% of it) on 4 clusters of small spheres "
                         "with a few big ones: choose, at each node, the plane that minimises "
                         "A_L |L| + A_R |R| over all axes and bins, not the middle object");
}

TEST_CASE_TEMPLATE("sah: closest hit through the SAH tree equals brute force", T, RT_SCALARS) {
    std::mt19937_64 rng(8103);
    objects<T> scene = clustered_scene<T>(rng);
    add_random_triangles(scene, rng, 100, 20, 3.0);
    const bvh<T> tree = build_sah_bounded(scene.boxes());
    const auto intersect = scene.intersector();
    int differ = 0;
    for (int i = 0; i < 400; ++i) {
        const ray<T> r = random_ray<T>(rng, 22);
        const auto want = brute_force(scene, r, rt::test::everything_ahead<T>());
        const auto got = closest_hit(tree, intersect, r, rt::test::everything_ahead<T>());
        differ += !same_answer(want, got);
    }
    CHECK_MESSAGE(differ == 0, differ << " of 400 rays got another answer through the SAH tree than from brute force; "
                                        "if the tree is valid (previous tests), the traversal is at fault");
}

TEST_CASE_TEMPLATE("sah: build_sah refuses options that cannot make a tree", T, RT_SCALARS) {
    std::vector<aabb<T>> boxes(3);
    for (size_t i = 0; i < boxes.size(); ++i) boxes[i].grow(vec3<T>(T(i), 0, 0));
    build_options no_leaves;
    no_leaves.max_leaf_size = 0;
    CHECK_THROWS_AS_MESSAGE(build_sah(boxes, no_leaves), std::invalid_argument,
                            "max_leaf_size 0 leaves no room for any object: throw std::invalid_argument");
    build_options one_bin;
    one_bin.bins = 1;
    CHECK_THROWS_AS_MESSAGE(build_sah(boxes, one_bin), std::invalid_argument,
                            "one bin has no plane between bins: throw std::invalid_argument");
}
